// The map describes itself (src/io/map_file.*): a map made by MapFile::create
// (MPI singleton) has a /schema entry for every /cases column and every
// per-case result dataset, units that match the core's parameter table, the
// same units and meanings as CF attributes on the datasets, and the dimension
// scales xarray names its dimensions by (/case, /sample, /grid/<axis>); the
// raw layout the run writes into is unchanged.
#include <gtest/gtest.h>
#include <hdf5_hl.h>
#include <mpi.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "io/case_row.hpp"
#include "io/h5.hpp"
#include "io/map_file.hpp"
#include "study/config.hpp"

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
};

// A 2 x 1 x 1 x 2 x 2 grid (d, R, tau, v, v1_over_v) with time series.
MadeMap make_map(const std::string& name) {
  MadeMap m;
  m.path = (std::filesystem::temp_directory_path() /
            ("mdrmap_schema_" + std::to_string(::getpid()) + "_" + name + ".h5"))
               .string();
  std::filesystem::remove(m.path);
  const std::vector<std::string> axes = {"d", "R", "tau", "v", "v1_over_v"};
  const std::vector<std::vector<double>> values = {{1e-3, 1e-2}, {1}, {1}, {0.1, 10}, {0, 0.5}};
  std::vector<mdrmap::study::StepRow> cases;
  for (double d : values[0])
    for (double v : values[3])
      for (double r : values[4]) {
        mdrmap::study::StepRow s;
        s.d = d, s.R = 1, s.tau = 1, s.v = v, s.v1 = r * v;
        cases.push_back(s);
      }
  m.spec.n_cases = cases.size();
  m.spec.samples = 5;
  m.spec.timeseries = true;
  m.spec.grid.names = axes;
  m.spec.grid.values = values;
  m.spec.grid.logarithmic = {1, 0, 0, 1, 0};
  io::Provenance prov;
  prov.config_text = "[grid]\n";
  io::MapFile::create(MPI_COMM_WORLD, m.path, m.spec, prov, cases);
  return m;
}

class MapSchema : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    io::silence_hdf5_errors();
    made_ = new MadeMap(make_map("grid"));
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

TEST_F(MapSchema, EveryCaseColumnHasTheParameterTablesUnitAndMeaning) {
  const auto cols = members(f(), "cases");
  ASSERT_EQ(cols.size(), 6u);
  for (const std::string& c : cols) {
    SCOPED_TRACE(c);
    const std::string entry = "schema/cases/" + c;
    ASSERT_TRUE(io::has_link(f(), entry));
    const mdrmap::ParamSpec* p = mdrmap::find_parameter(c);
    // v1 is the step's one history segment: the table's segment velocity
    const mdrmap::ParamSpec& spec = p ? *p : mdrmap::segment_velocity_spec();
    ASSERT_TRUE(p || c == "v1") << "a /cases column outside the parameter table";
    EXPECT_EQ(attr(f(), entry, "unit"), mdrmap::dim_name(spec.dim));
    if (p) {
      EXPECT_EQ(attr(f(), entry, "meaning"), p->meaning);
    }
    EXPECT_FALSE(attr(f(), entry, "meaning").empty());
    EXPECT_EQ(attr(f(), "cases/" + c, "units"), attr(f(), entry, "unit"));
    EXPECT_EQ(attr(f(), "cases/" + c, "long_name"), attr(f(), entry, "meaning"));
  }
  EXPECT_EQ(attr(f(), "schema/cases/d", "unit"), "length");
  EXPECT_EQ(attr(f(), "schema/cases/tau", "unit"), "time");
  EXPECT_EQ(attr(f(), "schema/cases/v", "unit"), "length/time");
  EXPECT_EQ(attr(f(), "schema/cases/v1", "unit"), "length/time");
  EXPECT_EQ(attr(f(), "schema/cases/G", "unit"), "force/length^2");
}

TEST_F(MapSchema, EveryResultDatasetIsDescribed) {
  std::size_t n = 0;
  for (const char* group : {"results", "analytic", "residuals", "timeseries"}) {
    for (const std::string& name : members(f(), group)) {
      const std::string path = std::string(group) + "/" + name, entry = "schema/" + path;
      SCOPED_TRACE(path);
      ++n;
      ASSERT_TRUE(io::has_link(f(), entry));
      const std::string unit = attr(f(), entry, "unit"), meaning = attr(f(), entry, "meaning");
      EXPECT_FALSE(unit.empty());
      EXPECT_FALSE(meaning.empty());
      EXPECT_EQ(attr(f(), path, "units"), unit);
      EXPECT_EQ(attr(f(), path, "long_name"), meaning);
      EXPECT_EQ(unit, io::result_info(path).unit);
      if (std::string(group) == "residuals") {
        EXPECT_EQ(unit, "number");
        EXPECT_EQ(meaning.rfind("(sim - analytic) / |analytic| of " + name, 0), 0u) << meaning;
      }
    }
  }
  // every row field, status, message and the five time series
  EXPECT_EQ(n, io::row_fields().size() + 2 + 5);
  EXPECT_EQ(attr(f(), "schema/results/FN_pre", "unit"), "force");
  EXPECT_EQ(attr(f(), "schema/results/mu_jump", "unit"), "number");
  EXPECT_EQ(attr(f(), "schema/results/a2_post", "unit"), "length");
  EXPECT_EQ(attr(f(), "schema/timeseries/t", "unit"), "time");
  // and nothing described that is not in the map
  for (const std::string& group : members(f(), "schema"))
    for (const std::string& name : members(f(), "schema/" + group))
      EXPECT_TRUE(io::has_link(f(), group + "/" + name)) << group << "/" << name;
}

TEST_F(MapSchema, GridAxesAreDescribedDimensionScales) {
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
  EXPECT_EQ(attr(f(), "schema/grid/v1_over_v", "unit"), "number");
}

TEST_F(MapSchema, PerCaseDatasetsAreAttachedToTheCaseAndSampleScales) {
  Handle c = io::make_dataset(H5Dopen2(f(), "case", H5P_DEFAULT), "opening /case");
  Handle s = io::make_dataset(H5Dopen2(f(), "sample", H5P_DEFAULT), "opening /sample");
  for (hid_t scale : {c.id(), s.id()}) {
    EXPECT_GT(H5DSis_scale(scale), 0);
    // no data: extent 0 of an unlimited maximum, nothing allocated
    EXPECT_EQ(H5Dget_storage_size(scale), 0u);
  }
  for (const char* group : {"cases", "results", "analytic", "residuals", "timeseries"})
    for (const std::string& name : members(f(), group)) {
      const std::string path = std::string(group) + "/" + name;
      SCOPED_TRACE(path);
      Handle d = io::make_dataset(H5Dopen2(f(), path.c_str(), H5P_DEFAULT), "open");
      EXPECT_GT(H5DSis_attached(d.id(), c.id(), 0), 0);
      if (std::string(group) == "timeseries") {
        EXPECT_GT(H5DSis_attached(d.id(), s.id(), 1), 0);
      }
    }
}

TEST_F(MapSchema, LayoutAndSizeBound) {
  std::vector<std::int8_t> status;
  const io::MapLayout layout = io::MapFile::read_layout(made_->path, &status);
  EXPECT_EQ(layout.n_cases, made_->spec.n_cases);
  EXPECT_EQ(layout.fields.size(), io::row_fields().size());
  EXPECT_EQ(layout.series.size(), 5u);
  const auto size = std::filesystem::file_size(made_->path);
  const auto bound = io::map_file_bytes(made_->spec, 8);
  EXPECT_LE(size, bound);
  EXPECT_LE(bound - size, 128u * 1024u);
}

} // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  MPI_Init(&argc, &argv);
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
