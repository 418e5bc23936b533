// A sweep's folder (docs/sweeps.md, "Outputs"). Unlike the other commands a sweep writes into DIR
// as it goes, so that it can resume: each finished sample appears whole or not at all.
//
// DIR/sweep.json           what made the folder: hashes of MESH, CONFIG, the sweep file (and a
//                          design table), the effective sweep, the design size; a rerun with
//                          other inputs is refused
// DIR/samples/NNNNNN.json  one finished sample: its values, outcome and timings (written to a
//                          temporary name, then renamed: present = finished)
// DIR/samples/NNNNNN.u     its displacement per model node (float64 x 3, mm): the start of later
//                          samples, also after a resume
// DIR/fields/NNNNNN.vtu    with save_fields: its solution (as `solve`'s solution.vtu, displacement)
// DIR/models/NNNNNN/model.feb|inp|scn   with export: its models
// DIR/results.csv, results.jsonl, summary.json, summary.txt, plots/*.svg
//                          written from the samples once all are there (or by --merge)
#pragma once

#include "app/html_outputs.h"
#include "app/job_config.h"
#include "core/model.h"
#include "workflows/landmarks.h"
#include "workflows/sweep_design.h"
#include "workflows/sweep_runner.h"
#include "workflows/sweep_spec.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace tissuemesh::app {

/// FNV-1a 64-bit hash of a file's bytes, as 16 hex digits; InputError when it cannot be read.
std::string file_hash(const std::string& path);

/// Creates DIR (and samples/) or checks that its sweep.json records the same `identity` (hashes and
/// design size): InputError naming the input that differs. Writes sweep.json when new.
void open_sweep_dir(const std::filesystem::path& dir, const nlohmann::json& identity, const nlohmann::json& record);

/// Indices of the samples DIR holds finished and converged (a failed sample is run again).
std::vector<int> finished_samples(const std::filesystem::path& dir);

/// The saved displacement fields of `indices` (those that have one), for warm starts.
std::map<int, std::vector<Eigen::Vector3d>> saved_fields(const std::filesystem::path& dir, const std::vector<int>& indices,
                                                          std::size_t nodes);

/// Landmarks a sweep follows (--points): their names, prone positions and places in the mesh.
struct SweepLandmarks {
  std::vector<Landmark> points;
  std::vector<LandmarkLocation> where;
};

/// Writes one finished sample atomically (json last), with its field, VTU and models as asked and
/// the landmarks' displaced positions.
void write_sample(const std::filesystem::path& dir, const Model& base, const JobConfig& config, const SweepSpec& spec,
                  const SweepLandmarks& landmarks, const SweepSample& sample, const SampleOutcome& outcome);

/// Writes results.csv, results.jsonl, summary.json, summary.txt and plots/ from the samples in DIR.
/// Returns the number of design samples missing (the files then hold the finished ones). With
/// `report`, also report.html: the base mesh, the sensitivity of each output, summary.txt.
int write_results(const std::filesystem::path& dir, const Model& base, const SweepSpec& spec,
                  const SweepLandmarks& landmarks, const std::vector<SweepSample>& design, RunReport* report = nullptr);

}  // namespace tissuemesh::app
