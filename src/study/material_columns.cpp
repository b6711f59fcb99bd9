#include "study/material_columns.hpp"

#include <algorithm>
#include <filesystem>

#include "core/model/params.hpp"
#include "material/card.hpp"
#include "study/config_detail.hpp"

namespace mdrmap::study::detail {
namespace {

const std::string kOption = "run.material";

/// One value of the card as a column of the study.
Axis card_column(const std::string& name, double x) {
  Axis a;
  a.name = name;
  a.section = "grid";
  a.spec = format_number(x);
  a.values = {x};
  a.given_by = kOption;
  parse_column(name, a.column);
  return a;
}

bool sets_spectrum(const Axis& a) {
  return a.column.spectrum() ||
         (a.column.kind == Column::Kind::Param && a.column.param == find_parameter("G"));
}

} // namespace

std::vector<Axis> read_material_columns(StudyConfig& c, const std::string& value,
                                        const std::string& base_dir) {
  const std::filesystem::path p(value);
  const std::string path = (p.is_absolute() || base_dir.empty())
                               ? value
                               : (std::filesystem::path(base_dir) / p).string();
  material::MaterialCard card;
  try {
    card = material::read_material(path);
  } catch (const InvalidInput& e) {
    throw ConfigError(kOption, std::string("material ") + e.what());
  }
  RunSettings& r = c.run;
  if (r.card_wlf) r.wlf.reset(), r.wlf_unit = TempUnit::None, r.card_wlf = false;
  if (card.wlf) {
    if (r.wlf)
      throw ConfigError(kOption, "the card " + path +
                                     " gives the WLF constants (*TRS), and [run] wlf gives them "
                                     "too; give them once: drop run.wlf or the card's *TRS");
    r.wlf = card.wlf->wlf, r.wlf_unit = card.wlf->unit, r.card_wlf = true;
  }
  r.material = path;
  r.material_text = card.text;
  std::vector<Axis> out = {card_column("G", card.G)};
  for (std::size_t k = 0; k < card.branches.size(); ++k) {
    out.push_back(card_column("G" + std::to_string(k + 1), card.branches[k].G));
    out.push_back(card_column("tau" + std::to_string(k + 1), card.branches[k].tau));
  }
  return out;
}

void refuse_beside_card(const StudyConfig& c, const Axis& a) {
  if (!sets_spectrum(a)) return;
  for (const Axis& b : c.axes) {
    if (!sets_spectrum(b) || b.by_default || b.given_by.empty() == a.given_by.empty()) continue;
    const Axis& own = a.given_by.empty() ? a : b;
    throw ConfigError(a.option(), "both [run] material (" + c.run.material +
                                      ", which gives G and the spectrum G1, tau1, ...) and " +
                                      own.option() +
                                      " are given; give the material once: the card or the keys");
  }
}

void refuse_wlf_beside_card(const RunSettings& r) {
  if (r.card_wlf)
    throw ConfigError("run.wlf", "both [run] material (" + r.material +
                                     ", whose *TRS gives the WLF constants) and wlf are given; "
                                     "give them once: drop wlf or the card's *TRS");
}

} // namespace mdrmap::study::detail
