// ExportOptions: the `export:` section of a config — per-format choices that are not part of the
// Model. Owned by code; unknown keys are errors.
//
//   export:
//     formats: [febio, abaqus, sofa, vtu, msh]   # what `tissuemesh export` writes by default
//     abaqus: {hybrid: false}       # true: C3D4H/C3D10H (Abaqus only; CalculiX rejects them)
//     febio: {linear_solver: ""}    # "" = FEBio's default (pardiso with MKL, else skyline)
//     sofa: {version: "25.06"}      # "24.06": StaticSolver with newton_iterations (v24.06-v24.12)
//                                   # "25.06": NewtonRaphsonSolver + StaticSolver (v25.06 and later)
#pragma once

#include "core/yaml_map.h"

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace tissuemesh {

struct AbaqusOptions {
  bool hybrid = false;  ///< C3D4H / C3D10H element types (Abaqus/Standard only)
};

struct FebioOptions {
  std::string linear_solver;  ///< "" (build default), "skyline", "pardiso", ...
};

struct SofaOptions {
  std::string version = "25.06";  ///< "24.06" or "25.06" (scene layout of the solver)
  std::string mesh_file = "model.vtk";  ///< companion mesh the scene's MeshVTKLoader reads
};

struct ExportOptions {
  std::vector<std::string> formats{"febio", "abaqus", "sofa", "vtu", "msh"};
  AbaqusOptions abaqus;
  FebioOptions febio;
  SofaOptions sofa;

  /// Reads an `export:` mapping; calls finish(). Throws InputError naming the key.
  static ExportOptions from_yaml(YamlMap& map);
  void to_yaml(YAML::Emitter& out) const;
};

}  // namespace tissuemesh
