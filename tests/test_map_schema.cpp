// The map describes itself (src/io/map_file.*, schema mdrmap-map/2): a map
// made by MapFile::create (MPI singleton) has a /schema entry for every
// /cases column and every per-case result dataset, units that match the
// core's parameter table, the same units and meanings as CF attributes on the
// datasets, per-event datasets [N, K] on the dimension `event`, `_FillValue`
// on the metrics that may be undefined, and the dimension scales xarray names
// its dimensions by (/case, /event, /sample, /grid/<axis>); /failures is
// written in place into the slots reserved at creation and read back; a map
// of the earlier schema is refused by name; a map's lock (io::MapLock) has
// one holder and survives the closing of other descriptors of the file.
#include <gtest/gtest.h>
#include <hdf5_hl.h>
#include <mpi.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/model/params.hpp"
#include "io/case_row.hpp"
#include "io/h5.hpp"
#include "io/map_file.hpp"
#include "io/map_lock.hpp"
#include "study/columns.hpp"
#include "study/config.hpp"
#include "study/preflight.hpp"

namespace {

namespace io = mdrmap::io;
using io::Handle;

// The names of the links of group `path` (sorted by name).
std::vector<std::string> members(hid_t file, const std::string& path) {
  std::vector<std::string> out;
  Handle g = io::make_group(H5Gopen2(file, path.c_str(), H5P_DEFAULT), "opening " + path);
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(name);
    return 0;
  };
  hsize_t idx = 0;
  io::check_status(H5Literate(g.id(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &out),
                   "listing " + path);
  return out;
}

std::string attr(hid_t file, const std::string& object, const std::string& name) {
  Handle o(io::check(H5Oopen(file, object.c_str(), H5P_DEFAULT), "opening " + object), H5Oclose);
  return io::read_string_attr(o.id(), name);
}

struct MadeMap {
  std::string path;
  io::MapSpec spec;
  std::vector<mdrmap::Case> cases;
};

std::string temp_map(const std::string& name) {
  const std::string p = (std::filesystem::temp_directory_path() /
                         ("mdrmap_schema_" + std::to_string(::getpid()) + "_" + name + ".h5"))
                            .string();
  std::filesystem::remove(p);
  return p;
}

/// A map of the study `ini` (a grid), made by MapFile::create as the runner makes it.
MadeMap make_map(const std::string& name, const std::string& ini) {
  namespace study = mdrmap::study;
  MadeMap m;
  m.path = temp_map(name);
  const study::StudyConfig cfg = study::parse_config(ini, "", name + ".ini");
  for (const study::Row& r : study::expand_cases(cfg))
    m.cases.push_back(study::case_for(cfg, r));
  m.spec = study::detail::map_spec(cfg, m.cases.size());
  io::Provenance prov;
  prov.config_text = ini;
  io::MapFile::create(MPI_COMM_WORLD, m.path, m.spec, prov, m.cases);
  return m;
}

// A 2 x 1 x 1 x 1 x 2 x 2 x 1 x 1 x 1 grid at fixed depth with two segments
// (a step or a hold, then a reslide) and time series.
const char* const kDepthIni = "[grid]\nd = 1e-3, 1e-2\nR = 1\ntau = 1\nv = 0.1, 10\n"
                              "[history]\nw1_over_v = 0, 0.5\nT1_over_tau = 1\nw2_over_v = 1\n"
                              "T2 = 2\n[run]\nsamples = 5\ntimeseries = true\n";

/// Unit and meaning of every dataset a map of `layout` may hold, by path.
std::map<std::string, io::FieldInfo> known_fields(const io::RowLayout& layout) {
  std::map<std::string, io::FieldInfo> out;
  for (const io::RowField& f : layout.fields())
    out[f.info.path] = f.info;
  for (const io::FieldInfo& f : layout.series())
    out[f.path] = f;
  for (const io::FieldInfo& f : io::other_result_info())
    out[f.path] = f;
  return out;
}

std::vector<hsize_t> shape(hid_t file, const std::string& path) {
  Handle d = io::make_dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), "opening " + path);
  Handle s = io::make_space(H5Dget_space(d.id()), "space of " + path);
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(s.id())));
  H5Sget_simple_extent_dims(s.id(), dims.data(), nullptr);
  return dims;
}

class MapSchema : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    io::silence_hdf5_errors();
    made_ = new MadeMap(make_map("grid", kDepthIni));
  }
  static void TearDownTestSuite() {
    std::filesystem::remove(made_->path);
    delete made_;
  }
  void SetUp() override {
    file_ = io::make_file(H5Fopen(made_->path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "opening");
  }
  hid_t f() const { return file_.id(); }
  static MadeMap* made_;
  Handle file_;
};
MadeMap* MapSchema::made_ = nullptr;

TEST_F(MapSchema, RootAttributesNameTheSchema) {
  EXPECT_EQ(io::read_string_attr(f(), "mdrmap_schema"), "mdrmap-map/2");
  EXPECT_EQ(std::string(io::kSchema), "mdrmap-map/2");
  EXPECT_EQ(io::read_string_attr(f(), "loading"), "depth");
  std::string why;
  EXPECT_TRUE(io::MapFile::is_map(made_->path, &why)) << why;
}

// The reference page (docs/reference/map-schema.md) lists the root attributes
// and /provenance from io::root_attributes() and io::provenance_info(): the
// map holds exactly those.
TEST_F(MapSchema, RootAttributesAndProvenanceAreTheDeclaredOnes) {
  std::vector<std::string> written;
  const auto collect = [](hid_t, const char* name, const H5A_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->push_back(name);
    return 0;
  };
  hsize_t idx = 0;
  ASSERT_GE(H5Aiterate2(f(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &written), 0);
  std::vector<std::string> declared;
  for (const io::RootAttribute& a : io::root_attributes())
    declared.push_back(a.name);
  std::sort(declared.begin(), declared.end());
  EXPECT_EQ(written, declared);
  std::vector<std::string> texts;
  for (const io::FieldInfo& t : io::provenance_info())
    texts.push_back(t.path.substr(t.path.find('/') + 1));
  std::vector<std::string> held;
  for (const std::string& m : members(f(), "provenance"))
    if (m.size() < 5 || m.compare(m.size() - 5, 5, "_byte") != 0)
      held.push_back(m); // not a dimension
  std::sort(texts.begin(), texts.end());
  EXPECT_EQ(held, texts);
  EXPECT_THROW(io::root_attribute("no_such_attribute"), std::logic_error);
}

TEST_F(MapSchema, EveryCaseColumnHasTheParameterTablesUnitAndMeaning) {
  const auto cols = members(f(), "cases");
  EXPECT_EQ(cols, std::vector<std::string>({"G", "R", "T", "d", "tau", "v", "w"}));
  const hsize_t N = made_->spec.n_cases, K = made_->spec.segments;
  for (const std::string& c : cols) {
    SCOPED_TRACE(c);
    const std::string entry = "schema/cases/" + c;
    ASSERT_TRUE(io::has_link(f(), entry));
    const mdrmap::ParamSpec* p = mdrmap::find_parameter(c);
    // w and T are the history's segments: the table's segment velocity and duration, [N, K]
    ASSERT_TRUE(p || c == "w" || c == "T") << "a /cases column outside the parameter table";
    const mdrmap::ParamSpec& spec =
        p ? *p : (c == "w" ? mdrmap::segment_velocity_spec() : mdrmap::segment_duration_spec());
    EXPECT_EQ(attr(f(), entry, "unit"), mdrmap::dim_name(spec.dim));
    if (p) {
      EXPECT_EQ(attr(f(), entry, "meaning"), p->meaning);
      EXPECT_EQ(shape(f(), "cases/" + c), std::vector<hsize_t>({N}));
    } else {
      EXPECT_EQ(shape(f(), "cases/" + c), std::vector<hsize_t>({N, K}));
    }
    EXPECT_FALSE(attr(f(), entry, "meaning").empty());
    EXPECT_EQ(attr(f(), "cases/" + c, "units"), attr(f(), entry, "unit"));
    EXPECT_EQ(attr(f(), "cases/" + c, "long_name"), attr(f(), entry, "meaning"));
  }
  EXPECT_EQ(attr(f(), "schema/cases/d", "unit"), "length");
  EXPECT_EQ(attr(f(), "schema/cases/tau", "unit"), "time");
  EXPECT_EQ(attr(f(), "schema/cases/v", "unit"), "length/time");
  EXPECT_EQ(attr(f(), "schema/cases/w", "unit"), "length/time");
  EXPECT_EQ(attr(f(), "schema/cases/T", "unit"), "time");
  EXPECT_EQ(attr(f(), "schema/cases/G", "unit"), "force/length^2");
}

TEST_F(MapSchema, CasesHoldTheHistoriesAsRun) {
  const std::size_t N = made_->spec.n_cases, K = made_->spec.segments;
  std::vector<double> w(N * K), T(N * K);
  Handle dw = io::make_dataset(H5Dopen2(f(), "cases/w", H5P_DEFAULT), "w");
  Handle dT = io::make_dataset(H5Dopen2(f(), "cases/T", H5P_DEFAULT), "T");
  ASSERT_GE(H5Dread(dw.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, w.data()), 0);
  ASSERT_GE(H5Dread(dT.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, T.data()), 0);
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t k = 0; k < K; ++k) {
      EXPECT_EQ(w[i * K + k], made_->cases[i].history.segments[k].w) << i << " " << k;
      EXPECT_EQ(T[i * K + k], made_->cases[i].history.segments[k].T) << i << " " << k;
    }
}

TEST_F(MapSchema, EveryResultDatasetIsDescribed) {
  const io::RowLayout layout = made_->spec.layout();
  const auto known = known_fields(layout);
  std::size_t n = 0;
  for (const char* group : {"results", "events", "analytic", "residuals", "scales", "timeseries"}) {
    for (const std::string& name : members(f(), group)) {
      const std::string path = std::string(group) + "/" + name, entry = "schema/" + path;
      SCOPED_TRACE(path);
      ++n;
      ASSERT_TRUE(io::has_link(f(), entry));
      ASSERT_EQ(known.count(path), 1u) << "a dataset the layout does not know";
      const std::string unit = attr(f(), entry, "unit"), meaning = attr(f(), entry, "meaning");
      EXPECT_FALSE(unit.empty());
      EXPECT_FALSE(meaning.empty());
      EXPECT_EQ(attr(f(), path, "units"), unit);
      EXPECT_EQ(attr(f(), path, "long_name"), meaning);
      EXPECT_EQ(unit, known.at(path).unit);
      EXPECT_EQ(meaning, known.at(path).meaning);
      if (std::string(group) == "residuals") {
        EXPECT_EQ(unit, "number");
        EXPECT_EQ(meaning.rfind("(", 0), 0u) << meaning;
        EXPECT_NE(meaning.find(") / |analytic/"), std::string::npos) << meaning;
      }
    }
  }
  // every row field, status, the time series and their segment index
  EXPECT_EQ(n, layout.fields().size() + 1 + layout.series().size() + 1);
  EXPECT_EQ(attr(f(), "schema/results/FN_pre", "unit"), "force");
  EXPECT_EQ(attr(f(), "schema/events/mu_peak", "unit"), "number");
  EXPECT_EQ(attr(f(), "schema/events/t_peak", "unit"), "time");
  EXPECT_EQ(attr(f(), "schema/events/D_c", "unit"), "length");
  EXPECT_EQ(attr(f(), "schema/analytic/a2_ss", "unit"), "length");
  EXPECT_EQ(attr(f(), "schema/timeseries/t", "unit"), "time");
  // and nothing described that is not in the map
  for (const std::string& group : members(f(), "schema"))
    for (const std::string& name : members(f(), "schema/" + group))
      EXPECT_TRUE(io::has_link(f(), group + "/" + name)) << group << "/" << name;
}

TEST_F(MapSchema, PerEventDatasetsAreNByKWithDimensionEvent) {
  const io::RowLayout layout = made_->spec.layout();
  const hsize_t N = made_->spec.n_cases, K = made_->spec.segments;
  ASSERT_EQ(K, 2u);
  Handle event = io::make_dataset(H5Dopen2(f(), "event", H5P_DEFAULT), "opening /event");
  EXPECT_GT(H5DSis_scale(event.id()), 0);
  std::size_t per_event = 0, fill = 0;
  for (const io::RowField& field : layout.fields()) {
    const std::string& path = field.info.path;
    SCOPED_TRACE(path);
    Handle d = io::make_dataset(H5Dopen2(f(), path.c_str(), H5P_DEFAULT), "open");
    if (field.per_event) {
      ++per_event;
      EXPECT_EQ(shape(f(), path), std::vector<hsize_t>({N, K}));
      EXPECT_GT(H5DSis_attached(d.id(), event.id(), 1), 0);
    } else {
      EXPECT_EQ(shape(f(), path), std::vector<hsize_t>({N}));
    }
    EXPECT_EQ(io::has_attr(d.id(), "_FillValue"), field.may_be_undefined);
    if (field.may_be_undefined) {
      ++fill;
      Handle a = io::make_attr(H5Aopen(d.id(), "_FillValue", H5P_DEFAULT), "_FillValue");
      double x = 0.0;
      ASSERT_GE(H5Aread(a.id(), H5T_NATIVE_DOUBLE, &x), 0);
      EXPECT_EQ(x, io::kFillValue);
    }
  }
  // a, b, a_minus_b, D_c, healing; at fixed depth also the seed's jump
  // estimate and its residuals (4 quantities each: undefined for a relaxation
  // spectrum)
  EXPECT_EQ(fill, layout.by_force() ? 5u : 13u);
  for (const char* p :
       {"events/a", "events/b", "events/a_minus_b", "events/D_c", "events/healing"}) {
    Handle d = io::make_dataset(H5Dopen2(f(), p, H5P_DEFAULT), p);
    EXPECT_TRUE(io::has_attr(d.id(), "_FillValue")) << p;
  }
  for (const char* p :
       {"events/t", "events/mu_peak", "events/mu_max", "events/mu_min", "events/mu_end",
        "analytic/mu_ss", "residuals/mu_end", "cases/w", "cases/T"}) {
    EXPECT_EQ(shape(f(), p), std::vector<hsize_t>({N, K})) << p;
  }
  for (const char* p : {"results/mu_pre", "analytic/mu_pre", "analytic/mu_jump",
                        "residuals/mu_jump", "results/status"}) {
    EXPECT_EQ(shape(f(), p), std::vector<hsize_t>({N})) << p;
  }
  EXPECT_GE(per_event, 20u);
}

TEST_F(MapSchema, GridAxesAreDescribedDimensionScales) {
  EXPECT_EQ(made_->spec.grid.names,
            std::vector<std::string>(
                {"d", "R", "tau", "G", "v", "w1_over_v", "T1_over_tau", "w2_over_v", "T2"}));
  for (const std::string& a : made_->spec.grid.names) {
    SCOPED_TRACE(a);
    Handle d = io::make_dataset(H5Dopen2(f(), ("grid/" + a).c_str(), H5P_DEFAULT), "open");
    EXPECT_GT(H5DSis_scale(d.id()), 0);
    char name[64] = {};
    ASSERT_GT(H5DSget_scale_name(d.id(), name, sizeof name), 0);
    EXPECT_EQ(std::string(name), a);
    ASSERT_TRUE(io::has_link(f(), "schema/grid/" + a));
    if (const mdrmap::ParamSpec* p = mdrmap::find_parameter(a)) {
      EXPECT_EQ(attr(f(), "schema/grid/" + a, "unit"), mdrmap::dim_name(p->dim));
    }
  }
  EXPECT_EQ(attr(f(), "schema/grid/w1_over_v", "unit"), "number");
  EXPECT_EQ(attr(f(), "schema/grid/T1_over_tau", "unit"), "number");
  EXPECT_EQ(attr(f(), "schema/grid/T2", "unit"), "time");
}

TEST_F(MapSchema, PerCaseDatasetsAreAttachedToTheCaseEventAndSampleScales) {
  Handle c = io::make_dataset(H5Dopen2(f(), "case", H5P_DEFAULT), "opening /case");
  Handle e = io::make_dataset(H5Dopen2(f(), "event", H5P_DEFAULT), "opening /event");
  Handle s = io::make_dataset(H5Dopen2(f(), "sample", H5P_DEFAULT), "opening /sample");
  for (hid_t scale : {c.id(), e.id(), s.id()}) {
    EXPECT_GT(H5DSis_scale(scale), 0);
    // no data: extent 0 of an unlimited maximum, nothing allocated
    EXPECT_EQ(H5Dget_storage_size(scale), 0u);
  }
  for (const char* group :
       {"cases", "results", "events", "analytic", "residuals", "scales", "timeseries"})
    for (const std::string& name : members(f(), group)) {
      const std::string path = std::string(group) + "/" + name;
      if (path == "timeseries/segment") continue; // [K S]: the sample dimension only
      SCOPED_TRACE(path);
      Handle d = io::make_dataset(H5Dopen2(f(), path.c_str(), H5P_DEFAULT), "open");
      EXPECT_GT(H5DSis_attached(d.id(), c.id(), 0), 0);
      if (std::string(group) == "timeseries") {
        EXPECT_GT(H5DSis_attached(d.id(), s.id(), 1), 0);
        EXPECT_EQ(shape(f(), path), std::vector<hsize_t>({made_->spec.n_cases, 2u * 5u}));
      }
    }
  Handle seg = io::make_dataset(H5Dopen2(f(), "timeseries/segment", H5P_DEFAULT), "segment");
  EXPECT_GT(H5DSis_attached(seg.id(), s.id(), 0), 0);
  std::vector<std::int32_t> segment(10);
  ASSERT_GE(H5Dread(seg.id(), H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, segment.data()), 0);
  EXPECT_EQ(segment, std::vector<std::int32_t>({0, 0, 0, 0, 0, 1, 1, 1, 1, 1}));
}

TEST_F(MapSchema, LayoutAndSizeBound) {
  std::vector<std::int8_t> status;
  const io::MapLayout layout = io::MapFile::read_layout(made_->path, &status);
  EXPECT_EQ(layout.n_cases, made_->spec.n_cases);
  EXPECT_EQ(layout.segments, 2u);
  EXPECT_FALSE(layout.by_force);
  EXPECT_TRUE(layout.timeseries);
  EXPECT_EQ(layout.fields.size(), made_->spec.layout().fields().size());
  EXPECT_EQ(layout.series.size(), 5u);
  EXPECT_EQ(status, std::vector<std::int8_t>(made_->spec.n_cases, 0));
  const io::MapLayout copy = io::MapLayout::unpack(layout.pack());
  EXPECT_EQ(copy.fields, layout.fields);
  EXPECT_EQ(copy.segments, layout.segments);
  const auto size = std::filesystem::file_size(made_->path);
  const auto bound = io::map_file_bytes(made_->spec, std::string(kDepthIni).size());
  EXPECT_LE(size, bound);
  EXPECT_LE(bound - size, 256u * 1024u);
}

// The prescribed load is /cases/F0 and the grid axis F0 (its old spelling FN
// in the config, as here, included: issue 22); the measured force is FN.
TEST(MapFile, LoadControlMap) {
  io::silence_hdf5_errors();
  const MadeMap m = make_map("load", "[grid]\nFN = 1e-3, 2e-3\nR = 1\ntau = 1\nv = 0.1\n"
                                     "[history]\nw1_over_v = 0\nT1_over_tau = 1\n"
                                     "[run]\nsamples = 3\n");
  Handle file = io::make_file(H5Fopen(m.path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "opening");
  const hid_t f = file.id();
  EXPECT_EQ(io::read_string_attr(f, "loading"), "force");
  EXPECT_EQ(members(f, "cases"), std::vector<std::string>({"F0", "G", "R", "T", "tau", "v", "w"}));
  EXPECT_EQ(attr(f, "schema/cases/F0", "unit"), "force");
  EXPECT_EQ(attr(f, "schema/cases/F0", "meaning").rfind("prescribed normal load", 0), 0U);
  EXPECT_TRUE(io::has_link(f, "grid/F0"));
  EXPECT_FALSE(io::has_link(f, "grid/FN"));
  EXPECT_TRUE(io::has_link(f, "results/FN_pre"));
  EXPECT_TRUE(io::has_link(f, "analytic/d_ss"));
  EXPECT_TRUE(io::has_link(f, "events/a1_end"));
  EXPECT_FALSE(io::has_link(f, "analytic/mu_jump")); // depth control only
  EXPECT_FALSE(io::has_link(f, "timeseries"));
  EXPECT_EQ(shape(f, "events/mu_peak"), std::vector<hsize_t>({2, 1}));
  file.reset();
  const io::MapLayout layout = io::MapFile::read_layout(m.path, nullptr);
  EXPECT_TRUE(layout.by_force);
  EXPECT_TRUE(layout.series.empty());
  std::filesystem::remove(m.path);
}

TEST(MapFile, FailuresWrittenAndReadBack) {
  io::silence_hdf5_errors();
  const MadeMap m = make_map("failures", kDepthIni);
  EXPECT_TRUE(io::MapFile::read_failures(m.path).empty()); // none at creation
  const std::vector<io::Failure> failures = {
      {1, "the solver refused: rtol must be a number in (0, 0.1], got 0.5"},
      {6, "x"},
      {7, std::string(300, 'm')}};
  const auto bytes = std::filesystem::file_size(m.path);
  io::MapFile::write_failures(m.path, failures);
  auto back = io::MapFile::read_failures(m.path);
  ASSERT_EQ(back.size(), failures.size());
  for (std::size_t i = 0; i < failures.size(); ++i) {
    EXPECT_EQ(back[i].index, failures[i].index);
    // a message longer than its slot is cut
    EXPECT_EQ(back[i].message, failures[i].message.substr(0, io::kFailureMessageBytes - 1));
  }
  EXPECT_EQ(back[2].message.size(), io::kFailureMessageBytes - 1);
  {
    Handle file = io::make_file(H5Fopen(m.path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "opening");
    EXPECT_EQ(attr(file.id(), "schema/failures/case", "unit"),
              io::other_info("failures/case").unit);
    EXPECT_EQ(attr(file.id(), "failures/message", "long_name"),
              io::other_info("failures/message").meaning);
  }
  // replaced, not appended; the map's layout is untouched
  io::MapFile::write_failures(m.path, {{3, "again"}});
  back = io::MapFile::read_failures(m.path);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].index, 3u);
  EXPECT_EQ(back[0].message, "again");
  io::MapFile::write_failures(m.path, {});
  EXPECT_TRUE(io::MapFile::read_failures(m.path).empty());
  // one slot per case (min(N, kMaxFailureSlots)): more failures than slots
  // keep the first ones
  std::vector<io::Failure> many;
  for (std::uint64_t i = 0; i < m.spec.n_cases + 4; ++i)
    many.push_back({i, "failure " + std::to_string(i)});
  io::MapFile::write_failures(m.path, many);
  back = io::MapFile::read_failures(m.path);
  ASSERT_EQ(back.size(), m.spec.n_cases);
  EXPECT_EQ(back.back().message, "failure " + std::to_string(m.spec.n_cases - 1));
  const io::MapLayout layout = io::MapFile::read_layout(m.path, nullptr);
  EXPECT_EQ(layout.n_cases, m.spec.n_cases);
  EXPECT_EQ(layout.failure_slots, m.spec.n_cases);
  // written in place, into the space reserved at creation: the file never grows
  EXPECT_EQ(std::filesystem::file_size(m.path), bytes);
  EXPECT_LE(bytes, io::map_file_bytes(m.spec, std::string(kDepthIni).size()));
  std::filesystem::remove(m.path);
}

TEST(MapLock, OneHolderThatOtherDescriptorsDoNotRelease) {
  const std::string p = temp_map("lock");
  std::ofstream(p) << "a map";
  io::MapLock a, b;
  long holder = -1;
  ASSERT_TRUE(a.acquire(p, &holder));
  a.announce();
  EXPECT_TRUE(a.held());
  EXPECT_TRUE(a.names(p));
  EXPECT_FALSE(b.acquire(p, &holder)); // another open file description: refused
  EXPECT_FALSE(b.held());
  // closing another descriptor of the file (as HDF5 does) drops POSIX record
  // locks, not this one
  const int fd = ::open(p.c_str(), O_RDONLY);
  ASSERT_GE(fd, 0);
  ::close(fd);
  EXPECT_FALSE(b.acquire(p, &holder));
  io::MapLock moved = std::move(a);
  EXPECT_FALSE(b.acquire(p, &holder));
  moved.release();
  EXPECT_TRUE(b.acquire(p, &holder));
  // a file renamed over keeps its lock, the path names another file then
  const std::string q = temp_map("lock_other");
  std::ofstream(q) << "another";
  EXPECT_EQ(io::rename_no_replace(q, p), EEXIST); // never over an existing file
  std::filesystem::rename(q, p);
  EXPECT_FALSE(b.names(p));
  std::filesystem::remove(p);
  EXPECT_EQ(io::rename_no_replace(p, q), ENOENT);
}

TEST(MapFile, SchemaOneIsRefusedByName) {
  io::silence_hdf5_errors();
  const std::string p = temp_map("old");
  {
    Handle file =
        io::make_file(H5Fcreate(p.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT), "creating");
    io::write_string_attr(file.id(), "mdrmap_schema", "mdrmap-map/1");
    file.close("closing");
  }
  std::string why;
  EXPECT_TRUE(io::MapFile::is_map(p, &why)) << why; // a map, of an earlier schema
  try {
    io::MapFile::read_layout(p, nullptr);
    ADD_FAILURE() << "read_layout took an mdrmap-map/1 map";
  } catch (const io::H5Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("mdrmap-map/1"), std::string::npos) << m;
    EXPECT_NE(m.find("mdrmap-map/2"), std::string::npos) << m;
    EXPECT_NE(m.find(p), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  std::filesystem::remove(p);
}

} // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  MPI_Init(&argc, &argv);
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
