#include "framework/core/stimulus_manifest.hpp"

#include <array>
#include <fstream>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/library_error.hpp"
#include "framework/core/write_file.hpp"

namespace crowdlab {
namespace {
const std::vector<std::string> kTrailing = {"file",   "duration_s", "frames", "width",      "height",
                                            "sha256", "overlap_l",  "v_i_m",  "collisions", "practice"};

/// The clip-quality columns (optional when read: older manifests lack them), in file order.
struct QualityColumn {
  const char* name;
  double ClipQuality::*value;  ///< null for the counts
  int ClipQuality::*count;     ///< the count, where value is null
};
constexpr std::array<QualityColumn, 17> kQuality = {
    {{"depth_p99_m", &ClipQuality::depth_p99_m, nullptr},
     {"depth_max_m", &ClipQuality::depth_max_m, nullptr},
     {"stance_foot_drift_p99_m", &ClipQuality::stance_foot_drift_p99_m, nullptr},
     {"stance_foot_drift_max_m", &ClipQuality::stance_foot_drift_max_m, nullptr},
     {"foot_pops", nullptr, &ClipQuality::foot_pops},
     {"foot_ground_penetration_max_m", &ClipQuality::foot_ground_penetration_max_m, nullptr},
     {"foot_ground_penetration_added_max_m", &ClipQuality::foot_ground_penetration_added_max_m, nullptr},
     {"foot_float_p99_m", &ClipQuality::foot_float_p99_m, nullptr},
     {"free_limb_dev_p99_deg", &ClipQuality::free_limb_dev_p99_deg, nullptr},
     {"free_limb_dev_max_deg", &ClipQuality::free_limb_dev_max_deg, nullptr},
     {"joint_flips", nullptr, &ClipQuality::joint_flips},
     {"env_penetration_p99_m", &ClipQuality::env_penetration_p99_m, nullptr},
     {"env_penetration_max_m", &ClipQuality::env_penetration_max_m, nullptr},
     {"mesh_overlap_fraction", &ClipQuality::mesh_overlap_fraction, nullptr},
     {"mesh_overlap_depth_p99_m", &ClipQuality::mesh_overlap_depth_p99_m, nullptr},
     {"proxy_coverage", &ClipQuality::proxy_coverage, nullptr},
     {"proxy_outside_p99_m", &ClipQuality::proxy_outside_p99_m, nullptr}}};

/// The stimulus-check columns (optional when read), in file order.
struct CheckColumn {
  const char* name;
  double StimulusCheck::*value;
};
constexpr std::array<CheckColumn, 5> kCheck = {
    {{"crowd_in_frame_min", &StimulusCheck::crowd_in_frame_min},
     {"character_height_px", &StimulusCheck::character_height_px},
     {"overlap_frame_share", &StimulusCheck::overlap_frame_share},
     {"overlap_pixel_fraction", &StimulusCheck::overlap_pixel_fraction},
     {"seam_step_ratio", &StimulusCheck::seam_step_ratio}}};

std::string optional_cell(double v) {
  return v >= 0 ? csv_number(v) : "";
}
}  // namespace

void write_manifest(const StimulusManifest& m, const std::string& csv_path) {
  std::string out;
  std::vector<std::string> header = {"id"};
  header.insert(header.end(), m.factor_names.begin(), m.factor_names.end());
  header.insert(header.end(), kTrailing.begin(), kTrailing.end());
  for (const QualityColumn& q : kQuality) header.push_back(q.name);
  for (const CheckColumn& c : kCheck) header.push_back(c.name);
  out += csv_line(header);
  for (const StimulusEntry& e : m.entries) {
    std::vector<std::string> row = {e.id};
    for (const auto& f : m.factor_names) {
      auto it = e.factors.find(f);
      row.push_back(it == e.factors.end() ? "" : it->second);
    }
    row.push_back(e.file);
    row.push_back(csv_number(e.duration_s));
    row.push_back(std::to_string(e.frames));
    row.push_back(std::to_string(e.width));
    row.push_back(std::to_string(e.height));
    row.push_back(e.sha256);
    row.push_back(optional_cell(e.mean_overlap_l));
    row.push_back(optional_cell(e.v_i_m));
    row.push_back(e.collisions >= 0 ? std::to_string(e.collisions) : "");
    row.push_back(e.practice ? "1" : "0");
    for (const QualityColumn& q : kQuality)
      row.push_back(q.value ? optional_cell(e.quality.*q.value)
                            : (e.quality.*q.count >= 0 ? std::to_string(e.quality.*q.count) : ""));
    for (const CheckColumn& c : kCheck) row.push_back(optional_cell(e.check.*c.value));
    out += csv_line(row);
  }
  // Atomically: a manifest is never seen half-written, and a full disk is reported with its reason.
  write_file_atomic(csv_path, out);
}

namespace {

StimulusManifest read_manifest_unwrapped(const std::string& csv_path) {
  const CsvTable t = read_csv(csv_path);
  StimulusManifest m;
  const size_t id_col = t.column("id");
  const size_t file_col = t.column("file");
  if (id_col != 0) throw InputError(csv_path + ": first column must be 'id'");
  for (size_t c = 1; c < file_col; ++c) m.factor_names.push_back(t.header[c]);
  for (const auto& name : kTrailing) t.column(name);  // all required
  auto optional_number = [&](size_t r, const std::string& col) {
    const size_t c = t.column(col);
    return t.cell(r, c).empty() ? -1.0 : t.number(r, c);
  };
  std::vector<bool> has_quality;
  for (const QualityColumn& q : kQuality) has_quality.push_back(t.has_column(q.name));
  std::vector<bool> has_check;
  for (const CheckColumn& c : kCheck) has_check.push_back(t.has_column(c.name));
  for (size_t r = 0; r < t.rows.size(); ++r) {
    StimulusEntry e;
    e.id = t.cell(r, id_col);
    for (size_t c = 1; c < file_col; ++c) e.factors[t.header[c]] = t.cell(r, c);
    e.file = t.cell(r, file_col);
    e.duration_s = t.number(r, t.column("duration_s"));
    e.frames = static_cast<int>(t.number(r, t.column("frames")));
    e.width = static_cast<int>(t.number(r, t.column("width")));
    e.height = static_cast<int>(t.number(r, t.column("height")));
    e.sha256 = t.cell(r, t.column("sha256"));
    e.mean_overlap_l = optional_number(r, "overlap_l");
    e.v_i_m = optional_number(r, "v_i_m");
    e.collisions = static_cast<int>(optional_number(r, "collisions"));
    e.practice = t.cell(r, t.column("practice")) == "1";
    for (size_t k = 0; k < kQuality.size(); ++k) {
      if (!has_quality[k]) continue;
      const double v = optional_number(r, kQuality[k].name);
      if (kQuality[k].value)
        e.quality.*kQuality[k].value = v;
      else
        e.quality.*kQuality[k].count = static_cast<int>(v);
    }
    for (size_t k = 0; k < kCheck.size(); ++k)
      if (has_check[k]) e.check.*kCheck[k].value = optional_number(r, kCheck[k].name);
    m.entries.push_back(std::move(e));
  }
  return m;
}

}  // namespace

StimulusManifest read_manifest(const std::string& csv_path) {
  // A library's exception the column checks miss names the manifest (issue 33).
  return at_input_boundary(csv_path, [&] { return read_manifest_unwrapped(csv_path); });
}

}  // namespace crowdlab
