// tissuemesh sweep MESH -c CONFIG --sweep SWEEP.yaml -o DIR [--jobs N] [--shard I/N] [--merge]
// [--no-warm-start] [--points P.csv] [--slurm N [--submit]]: one solve per sample of a parameter design, resumable (app/sweep_outputs.h).
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/export_outputs.h"
#include "app/job_config.h"
#include "app/sweep_outputs.h"
#include "app/sweep_slurm.h"
#include "core/errors.h"
#include "fe_export/registry.h"
#include "workflows/step_models.h"
#include "workflows/sweep_parameters.h"

#include <algorithm>
#include <atomic>
#include <fstream>
#include <sstream>
#include <csignal>
#include <iostream>
#include <memory>
#include <thread>

#include <unistd.h>

namespace tissuemesh::app {

namespace {

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

struct SweepCliOptions : ModelJobOptions {
  std::string sweep, shard, points;
  int jobs = 1, threads = 0, slurm = 0;
  bool merge = false, no_warm_start = false, submit = false, no_html = false;
};

/// "I/N" with 1 <= I <= N.
std::pair<int, int> parse_shard(const std::string& text) {
  int i = 0, n = 0;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || !(in >> std::ws).eof() || n < 1 || i < 1 || i > n)
    throw InputError("--shard " + text + ": expected I/N with 1 <= I <= N (e.g. 2/4)");
  return {i, n};
}

}  // namespace

void add_sweep_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<SweepCliOptions>();
  CLI::App* sub = cli.add_subcommand(
      "sweep",
      "Solve the model of MESH + CONFIG once per sample of a parameter design (SWEEP.yaml: parameters by config path, "
      "grid / lhs / sobol / table): DIR/results.csv, results.jsonl, summary.json, summary.txt (ranges, standardised "
      "regression coefficients, Sobol' indices), plots/*.svg. Resumable: rerun the same command to finish an "
      "interrupted sweep. A sample that fails is a row with converged=false, not a stopped sweep.");
  add_model_job_options(*sub, *opt);
  sub->add_option("--sweep", opt->sweep, "the sweep file (parameters, design)")->required();
  sub->add_option("--jobs", opt->jobs, "samples run side by side (default 1)")->check(CLI::PositiveNumber);
  sub->add_option("--threads", opt->threads,
                  "assembly threads per sample (default 0: the processors divided among the jobs)")
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--shard", opt->shard, "run only part I of N of the design (samples i with i mod N = I - 1)");
  sub->add_option("--points", opt->points,
                  "landmarks CSV 'name,x,y,z' (LPS mm, in the mesh): each sample's displaced positions in results.csv");
  sub->add_flag("--merge", opt->merge, "write results and summary from the samples in DIR (after sharded runs)");
  sub->add_flag("--no-warm-start", opt->no_warm_start, "start every solve from zero");
  add_html_flag(*sub, opt->no_html);
  sub->add_option("--slurm", opt->slurm,
                  "write DIR/sweep.sbatch (a Slurm job array of N shards) and DIR/merge.sbatch (the merge, after the "
                  "array); run nothing here")
      ->check(CLI::Range(1, 10000));
  sub->add_flag("--submit", opt->submit, "with --slurm: submit both with sbatch (the merge depends on the array)");
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("sweep", [&] {
      const JobConfig config = JobConfig::load(opt->config);
      const SweepSpec spec = SweepSpec::load(opt->sweep);
      if (opt->print_config) {
        std::cout << config.to_yaml() << "---\n" << spec.to_yaml();
        return;
      }
      require_report_assets(!opt->no_html);
      if (opt->out.empty()) throw InputError("-o DIR is required");
      Progress progress = console_progress();
      // prone2supine samples need the sliding sets of either step built with their normals.
      JobConfig build = config;
      if (spec.analysis == "prone2supine") build.model = settings_for_steps(config.model, config.prone2supine);
      JobModel job;
      job.inputs = job_inputs(opt->mesh, config);
      job.model = build_job_model(read_job_mesh(opt->mesh, progress), build, progress);
      if (spec.analysis == "prone2supine" && !(job.model.gravity.acceleration_m_s2.norm() > 0.0))
        throw InputError(config.source + ": model.gravity is none: a prone2supine sweep needs the prone gravity");
      for (const SweepParameter& p : spec.parameters) check_parameter_path(job.model, p.path);
      SweepLandmarks landmarks;
      if (!opt->points.empty()) {
        landmarks.points = read_landmarks_csv(opt->points);
        landmarks.where = locate_landmarks(job.model, landmarks.points);
      }
      const std::vector<SweepSample> design = make_design(spec);
      const std::filesystem::path dir(opt->out);
      nlohmann::json identity = {{"mesh", file_hash(opt->mesh)},
                                 {"config", file_hash(opt->config)},
                                 {"sweep file", file_hash(opt->sweep)},
                                 {"design size", design.size()}};
      if (spec.design == DesignType::Table) identity["design table"] = file_hash(spec.table_file);
      if (!opt->points.empty()) identity["points file"] = file_hash(opt->points);
      nlohmann::json record = run_record_common(progress, run.command_line);
      record["inputs"] = job.inputs;
      record["inputs"]["sweep"] = std::filesystem::absolute(opt->sweep).string();
      record["sweep"] = spec.to_yaml();
      record["config"] = {{"source", config.source}, {"effective_yaml", config.to_yaml()}};
      record["model"] = model_summary_json(job.model);
      // A format that cannot write this model is refused before any sample runs.
      if (!spec.exports.empty()) {
        const std::filesystem::path probe = std::filesystem::temp_directory_path() /
                                            ("tissuemesh-export-check-" + std::to_string(::getpid()));
        std::filesystem::create_directories(probe);
        try {
          for (const std::string& f : spec.exports) {
            const ExportFormat& format = export_format_named(f);
            export_model(job.model, format, (probe / format.default_file).string(), config.exports);
          }
        } catch (...) {
          std::filesystem::remove_all(probe);
          throw;
        }
        std::filesystem::remove_all(probe);
      }
      open_sweep_dir(dir, identity, record);

      if (opt->slurm > 0) {
        std::vector<std::string> args = {"sweep", std::filesystem::absolute(opt->mesh).string(), "-c",
                                         std::filesystem::absolute(opt->config).string(), "--sweep",
                                         std::filesystem::absolute(opt->sweep).string(), "-o",
                                         std::filesystem::absolute(dir).string()};
        if (opt->no_warm_start) args.push_back("--no-warm-start");
        if (!opt->points.empty()) args.insert(args.end(), {"--points", std::filesystem::absolute(opt->points).string()});
        const SlurmScripts scripts = write_slurm_scripts(dir, args, opt->slurm);
        std::cout << "wrote " << scripts.array.string() << " (" << opt->slurm << " shards) and " << scripts.merge.string()
                  << "\n";
        if (opt->submit) {
          const std::string ids = submit_slurm(scripts);
          std::cout << "submitted: " << ids << "; results in " << dir.string() << "/results.csv when the merge job ends\n";
        } else {
          std::cout << "submit with: jid=$(sbatch --parsable " << scripts.array.string()
                    << ") && sbatch --dependency=afterok:$jid " << scripts.merge.string() << "\n";
        }
        return;
      }
      if (opt->submit) throw InputError("--submit needs --slurm N");
      if (!opt->merge) {
        const std::vector<int> done = finished_samples(dir);
        std::vector<int> todo;
        int shard = 1, shards = 1;
        if (!opt->shard.empty()) std::tie(shard, shards) = parse_shard(opt->shard);
        for (const SweepSample& s : design)
          if (s.index % shards == shard - 1 && !std::binary_search(done.begin(), done.end(), s.index))
            todo.push_back(s.index);
        SweepRunOptions options;
        options.jobs = opt->jobs;
        const int cores = std::max(1u, std::thread::hardware_concurrency());
        options.threads_per_job = opt->threads > 0 ? opt->threads : std::max(1, cores / opt->jobs);
        options.warm_start = !opt->no_warm_start && spec.analysis == "solve";
        options.model_settings = config.model;
        options.prone2supine = config.prone2supine;
        if (options.warm_start && !todo.empty()) {
          std::vector<int> near;  // only the fields a start can still come from
          for (int d : done)
            if (d >= todo.front() - options.warm_window) near.push_back(d);
          options.finished_fields = saved_fields(dir, near, job.model.nodes.size());
        }
        g_stop = false;
        std::signal(SIGINT, on_signal);
        std::signal(SIGTERM, on_signal);
        options.should_stop = [] { return g_stop.load(); };
        auto stage = progress.stage("sweep: " + std::to_string(todo.size()) + " samples to run of " +
                                    std::to_string(design.size()) + " (" + std::to_string(done.size()) +
                                    " finished before), " + std::to_string(options.jobs) + " job(s) x " +
                                    std::to_string(options.threads_per_job) + " thread(s)");
        int finished = 0;
        options.on_finished = [&](const SweepSample& s, const SampleOutcome& o) {
          write_sample(dir, job.model, config, spec, landmarks, s, o);
          ++finished;
          stage.note("sample " + std::to_string(s.index) + " (" + std::to_string(finished) + "/" +
                     std::to_string(todo.size()) + "): " + (o.converged ? "max |u| " + format_double("%.4f", o.max_displacement_mm) + " mm"
                                                                         : "FAILED: " + o.message) +
                     ", " + std::to_string(o.newton_iterations) + " Newton iterations" +
                     (o.warm_from >= 0 ? " from sample " + std::to_string(o.warm_from) : " from zero") + ", " +
                     format_double("%.2f", o.seconds) + " s",
                     static_cast<double>(finished) / static_cast<double>(todo.size()));
        };
        run_samples(job.model, spec, design, todo, options);
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);
        if (g_stop)
          throw SolverError("interrupted after " + std::to_string(finished) + " of " + std::to_string(todo.size()) +
                            " samples; run the same command again to resume");
        if (!opt->shard.empty()) {
          std::cout << "shard " << shard << "/" << shards << ": " << finished << " samples written to " << dir.string()
                    << "/samples; `tissuemesh sweep ... --merge` writes the results once every shard is done\n";
          return;
        }
      }
      int missing = 0;
      {
        auto stage = progress.stage("results and summary");
        RunReport report(!opt->no_html, "tissuemesh sweep: " + opt->sweep, run.command_line);
        missing = write_results(dir, job.model, spec, landmarks, design, &report);
      }
      {
        std::ifstream summary(dir / "summary.txt");
        std::cout << summary.rdbuf();
      }
      std::cout << "wrote " << dir.string() << "/{results.csv, results.jsonl, summary.json, summary.txt, plots/"
                << (opt->no_html ? "" : ", report.html") << "}\n";
      if (missing > 0)
        throw SolverError(std::to_string(missing) + " of " + std::to_string(design.size()) +
                          " samples are not finished (the results hold the others); run the missing shards");
    });
  });
}

}  // namespace tissuemesh::app
