// tissuemesh info FILE: what a label image or a mesh holds.
#include "app/cli_support.h"
#include "app/commands.h"
#include "core/errors.h"
#include "core/vtu_io.h"
#include "image/image_io.h"
#include "pipeline/mesh_report.h"

#include <iostream>
#include <memory>

namespace tissuemesh::app {

namespace {
struct InfoOptions {
  std::string file;
  bool json = false;
};
bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

void add_info_command(CLI::App& cli, Invocation& run) {
  auto opt = std::make_shared<InfoOptions>();
  CLI::App* sub = cli.add_subcommand(
      "info", "Show a label image (dims, spacing, orientation, label counts) or a mesh (quality, conformity)");
  sub->add_option("FILE", opt->file, "label image (.nii, .nii.gz, .nrrd, .nhdr, .mha, .mhd) or mesh (.vtu)")->required();
  sub->add_flag("--json", opt->json, "print JSON instead of text");
  sub->callback([opt, &run] {
    run.exit_code = run_guarded("info", [&] {
      if (ends_with(opt->file, ".vtu")) {
        const TetMesh mesh = read_vtu(opt->file);
        std::cout << (opt->json ? mesh_summary_json(mesh).dump(2) + "\n" : mesh_summary_text(mesh));
      } else {
        const LabelImage image = read_label_image(opt->file);
        std::cout << (opt->json ? image_summary_json(image).dump(2) + "\n" : image_summary_text(image));
      }
    });
  });
}

}  // namespace tissuemesh::app
