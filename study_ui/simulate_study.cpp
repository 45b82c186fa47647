#include "study_ui/simulate_study.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "study_ui/response_log.hpp"
#include "study_ui/run_session.hpp"
#include "study_ui/simulated_presenter.hpp"
#include "study_ui/verify_stimuli.hpp"

namespace crowdlab::study {

std::string simulated_participant_id(int i) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "S%03d", i + 1);
  return buf;
}

std::string simulate_study(const ExperimentSpec& spec, const StimulusManifest& manifest,
                           const ObserverModel& model, const SimulateStudyOptions& opt) {
  if (opt.observers < 1)
    throw InputError(SourceLocation{"", 0, 0, "--observers"}, "need at least 1 observer");
  if (opt.verify_files) verify_stimuli(manifest, opt.stimuli_dir);
  const std::string merged = (std::filesystem::path(opt.out_dir) / "responses.csv").string();
  if (std::filesystem::exists(merged))
    throw InputError(merged + ": already exists; choose an empty --out folder");
  std::string merged_text;
  Progress progress("simulating observers", static_cast<size_t>(opt.observers));
  for (int i = 0; i < opt.observers; ++i) {
    const std::string id = simulated_participant_id(i);
    SimulatedPresenter presenter(model, derive_seed(opt.seed, "observer:" + id));
    SessionOptions so;
    so.participant = id;
    so.stimuli_dir = opt.stimuli_dir;
    so.out_dir = opt.out_dir;
    so.presenter_name = "simulated";
    so.simulated = true;
    so.verify_files = false;  // verified once above
    so.durable = false;       // synthetic and regenerable from the seed: no per-trial fsync
    const SessionResult r = run_session(spec, manifest, so, presenter);
    std::ifstream in(r.csv_path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    if (i > 0) text.erase(0, text.find('\n') + 1);  // one header
    merged_text += text;
    progress.advance();
  }
  write_file_atomically(merged, merged_text);
  return merged;
}

}  // namespace crowdlab::study
