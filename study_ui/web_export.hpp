#pragma once
// export_web: a spec's study as a static jsPsych web experiment (and a JATOS study archive), with
// the same protocol and the same per-participant trial order as the native session (run_session).
//
// Output folder (WEBDIR):
//   index.html, crowdlab_study.js, crowdlab_study.css   our page and script, copied from study_ui/web
//                                                       (copies, never links: editing an export must
//                                                       not edit the source or other exports)
//   lib/jspsych.js, lib/jspsych.css, lib/plugin-*.js     jsPsych 8 and the plugins the page uses
//                                                       (preload, fullscreen), copied from the build
//                                                       tree's node_modules (make web-deps)
//   lib/LICENSE-jspsych.txt                             jsPsych's MIT notice (study_ui/web), which the
//                                                       licence requires with every copy
//   <manifest file paths>                               the clips, hard-linked (copied across devices)
//   timeline.json                                       web_timeline() below
// Trial orders: computed here by build_trial_list for every id in `participants` and embedded, so the
// browser runs no randomisation of its own and the web order equals `crowdlab study`'s for that id.
// An id that is not embedded (a panel's PROLIFIC_PID, say) takes the order of the embedded id
// web_order_participant() picks: ids[fnv1a32(id) mod ids.size()] (FNV-1a, 32 bit, over the id's
// bytes; http://www.isthe.com/chongo/tech/comp/fnv/). The data record it under `order_of`, and
// import-web checks the answers against that order.
// JATOS archive (.jzip, https://www.jatos.org/JATOS-Study-Archive-JZIP.html): a ZIP holding, at its top
// level, exactly one <dir>.jas and one folder <dir>/ with WEBDIR's files (JATOS moves that folder into
// its study assets; it refuses archives with two .jas files or two folders, ImportExportService). The
// .jas is jatos_study_json(): "version": "3" and "data" with the fields of JATOS's documented example
// and JSON schema, in their order (study uuid, title, description, flags, dirName, comments, jsonData,
// endRedirectUrl, studyEntryMsg, componentList with one component, batchList with one "Default"
// batch). The uuids derive from the spec's name, so exporting a changed spec again replaces the same
// study.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::study {

/// The default embedded ids: P01 .. PNN (zero-padded to at least two digits, like the native examples).
std::vector<std::string> numbered_participant_ids(int count);

/// FNV-1a 32-bit hash of the id's bytes (offset basis 2166136261, prime 16777619).
std::uint32_t fnv1a32(const std::string& text);

/// The embedded id whose order a participant runs: the id itself when embedded, else the hashed slot.
std::string web_order_participant(const std::string& participant, const std::vector<std::string>& embedded);

/// The timeline.json object: study settings, questions, the participant id rule (participant_id.hpp),
/// the inter-trial screen, stimuli, and per embedded id its trial order ("orders") and its session
/// plan ("plans", session_plan.hpp's plan_steps_json), which the page interprets. Throws InputError
/// (via build_trial_list / resolve_questions) on a bad protocol.
nlohmann::json web_timeline(const ExperimentSpec& spec, const StimulusManifest& manifest,
                            const std::string& manifest_sha256, const std::vector<std::string>& participants);

/// The JATOS study properties (.jas) for the study assets folder `dir_name`.
nlohmann::ordered_json jatos_study_json(const ExperimentSpec& spec, const std::string& dir_name);

struct WebExportOptions {
  std::string stimuli_dir;                ///< folder of manifest.csv
  std::string out_dir;                    ///< WEBDIR; must be absent or empty
  std::string jatos_path;                 ///< .jzip to write ("" = none)
  std::vector<std::string> participants;  ///< embedded ids (each checked like --participant)
  std::string web_source_dir;             ///< study_ui/web
  std::string node_modules_dir;           ///< holds jspsych/ and @jspsych/plugin-*/
};

struct WebExportResult {
  int files = 0;  ///< files written into WEBDIR
  int clips = 0;
  long bytes = 0;
  std::string jatos_dir;  ///< the study-assets folder name inside the .jzip
};

/// The jsPsych files a web study loads: (path under node_modules, path under WEBDIR).
std::vector<std::pair<std::string, std::string>> jspsych_bundle_files();

WebExportResult export_web(const ExperimentSpec& spec, const StimulusManifest& manifest,
                           const WebExportOptions& options);

}  // namespace crowdlab::study
