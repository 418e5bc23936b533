// tissuemesh phantom --out FILE [--kind K] [--no-background] [--seed N] [...]: a built-in phantom
// (the smooth breast, the fragmented breast, the folded layers) as a label image.
#include "app/cli_support.h"
#include "app/commands.h"
#include "app/job_config.h"
#include "core/errors.h"
#include "core/output_dir.h"
#include "image/image_io.h"
#include "pipeline/mesh_report.h"
#include "image/make_phantom.h"
#include "image/phantom.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

namespace tissuemesh::app {

namespace {
struct PhantomOptions {
  std::string out, config;
  std::optional<unsigned> seed;
  std::vector<double> tumor_center, spacing;
  std::optional<double> tumor_diameter;
  std::optional<std::string> kind;
  bool no_background = false;
};
}  // namespace

void add_phantom_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<PhantomOptions>();
  CLI::App* sub = cli.add_subcommand("phantom", "Write a built-in phantom as NIfTI: the breast (labels 0 air, 1 fat, "
                                                "2 fgt, 3 tumor, 4 skin, 5 muscle, 6 thorax), the fragmented breast "
                                                "(+ 7 vessel, 8 clip) or the folded layers");
  sub->add_option("--out", opt->out, "output label image (.nii or .nii.gz); a run record FILE.json goes beside it")
      ->required();
  sub->add_option("-c,--config", opt->config, "config whose `phantom:` section sets the parameters");
  sub->add_option("--kind", opt->kind, "breast (default), fragmented-breast or folded-layers")
      ->check(CLI::IsMember({"breast", "fragmented-breast", "folded-layers"}));
  sub->add_flag("--no-background", opt->no_background,
                "no label 0: tissue up to every face of the box, plus a tiny tissue (33 voxels)");
  sub->add_option("--seed", opt->seed, "random seed of the generator (default 1)");
  sub->add_option("--tumor-center", opt->tumor_center, "tumour centre, LPS mm (3 values)")->expected(3)->delimiter(',');
  sub->add_option("--tumor-diameter", opt->tumor_diameter, "tumour diameter, mm (default 15)");
  sub->add_option("--spacing", opt->spacing, "voxel spacing i,j,k in mm (default 0.7,0.7,1.5)")->expected(3)->delimiter(',');
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("phantom", [&] {
      PhantomParams params = opt->config.empty() ? MeshConfig::phantom_default().phantom
                                                 : JobConfig::load(opt->config).require_mesh().phantom;
      if (opt->kind) params.kind = *opt->kind;
      if (opt->no_background) params.no_background = true;
      if (params.kind == "breast") {
        if (opt->seed) params.seed = *opt->seed;
        if (!opt->tumor_center.empty()) params.tumor_center_mm = Eigen::Vector3d(opt->tumor_center.data());
        if (opt->tumor_diameter) params.tumor_diameter_mm = *opt->tumor_diameter;
        if (!opt->spacing.empty()) params.spacing_mm = Eigen::Vector3d(opt->spacing.data());
      } else {
        if (!opt->tumor_center.empty() || !opt->spacing.empty() || opt->tumor_diameter)
          throw InputError("phantom: --tumor-center, --tumor-diameter and --spacing set the breast kind only; "
                           "set the " + params.kind + " parameters in the config's phantom section");
        if (opt->seed) (params.kind == "fragmented-breast" ? params.fragmented_breast.seed : params.folded_layers.seed) = *opt->seed;
      }

      const std::filesystem::path target = std::filesystem::absolute(opt->out);
      OutputDir out(target.parent_path());
      Progress progress = console_progress();
      LabelImage image;
      {
        auto stage = progress.stage("generate phantom");
        image = make_phantom(params);
      }
      {
        auto stage = progress.stage("write " + target.filename().string());
        write_nifti(image, out.stage(target.filename().string()).string());
      }
      nlohmann::json record = run_record_common(progress, run.command_line);
      YAML::Emitter yaml;
      phantom_params_to_yaml(params, yaml);
      record["phantom_parameters_yaml"] = std::string(yaml.c_str());
      record["image"] = image_summary_json(image);
      record["outputs"] = {{"labels", target.string()}};
      {
        const auto json_path = out.stage(target.filename().string() + ".json");
        std::ofstream json(json_path);
        json << record.dump(2) << "\n";
        if (!json.flush()) throw OutputError(json_path.string() + ": cannot write run record");
      }
      out.commit();
      std::cout << image_summary_text(image) << "wrote " << target.string() << "\n";
    });
  });
}

}  // namespace tissuemesh::app
