#include "app/sweep_outputs.h"

#include "app/cli_support.h"
#include "app/solve_outputs.h"
#include "core/errors.h"
#include "fe_export/registry.h"
#include "fe_export/vtu/write_model_vtu.h"
#include "workflows/sensitivity.h"
#include "workflows/sweep_parameters.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace tissuemesh::app {

namespace {

std::string sample_name(int index) {
  char name[16];
  std::snprintf(name, sizeof name, "%06d", index);
  return name;
}

/// Writes `text` to `path` through a temporary file and a rename (whole or not at all).
void write_atomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    if (!f.flush()) throw OutputError(tmp.string() + ": cannot write");
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw OutputError(path.string() + ": cannot write: " + ec.message());
}

std::string number(double v) { return format_double("%.9g", v); }

std::string csv_text(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c == '\n' ? ' ' : c;
  }
  return out + "\"";
}

/// The scalar outputs a summary ranks, from one sample's record.
std::vector<std::pair<std::string, double>> scalar_outputs(const nlohmann::json& s) {
  std::vector<std::pair<std::string, double>> out;
  out.emplace_back("max_displacement_mm", s["max_displacement_mm"].get<double>());
  for (const auto& t : s["tissues"]) {
    const std::string name = t["name"].get<std::string>();
    if (name == "tumor" || name == "tumour") out.emplace_back("tumour_displacement_mm", t["mean_displacement_magnitude_mm"].get<double>());
  }
  for (const auto& t : s["tissues"])
    out.emplace_back(t["name"].get<std::string>() + "_mean_displacement_mm", t["mean_displacement_magnitude_mm"].get<double>());
  return out;
}

// A scatter plot of y against x as SVG (log x axis when asked).
std::string scatter_svg(const std::string& title, const std::string& xlabel, const std::string& ylabel,
                        const std::vector<double>& x, const std::vector<double>& y, bool log_x) {
  const double W = 420, H = 300, L = 70, R = 20, T = 30, B = 50;
  auto tx = [&](double v) { return log_x ? std::log10(v) : v; };
  double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
  for (std::size_t i = 0; i < x.size(); ++i) {
    x0 = std::min(x0, tx(x[i]));
    x1 = std::max(x1, tx(x[i]));
    y0 = std::min(y0, y[i]);
    y1 = std::max(y1, y[i]);
  }
  if (!(x1 > x0)) { x0 -= 0.5; x1 += 0.5; }
  if (!(y1 > y0)) { y0 -= 0.5; y1 += 0.5; }
  auto px = [&](double v) { return L + (tx(v) - x0) / (x1 - x0) * (W - L - R); };
  auto py = [&](double v) { return H - B - (v - y0) / (y1 - y0) * (H - T - B); };
  std::ostringstream s;
  s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  s << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s << "<text x=\"" << W / 2 << "\" y=\"18\" text-anchor=\"middle\" font-size=\"13\">" << title << "</text>\n";
  s << "<line x1=\"" << L << "\" y1=\"" << H - B << "\" x2=\"" << W - R << "\" y2=\"" << H - B << "\" stroke=\"black\"/>\n";
  s << "<line x1=\"" << L << "\" y1=\"" << T << "\" x2=\"" << L << "\" y2=\"" << H - B << "\" stroke=\"black\"/>\n";
  auto xtick = [&](double v) { return format_double("%.4g", log_x ? std::pow(10.0, v) : v); };
  s << "<text x=\"" << L << "\" y=\"" << H - B + 15 << "\" text-anchor=\"start\">" << xtick(x0) << "</text>\n";
  s << "<text x=\"" << W - R << "\" y=\"" << H - B + 15 << "\" text-anchor=\"end\">" << xtick(x1) << "</text>\n";
  s << "<text x=\"" << (L + W - R) / 2 << "\" y=\"" << H - 12 << "\" text-anchor=\"middle\">" << xlabel
    << (log_x ? " (log scale)" : "") << "</text>\n";
  s << "<text x=\"" << L - 5 << "\" y=\"" << H - B << "\" text-anchor=\"end\">" << format_double("%.4g", y0) << "</text>\n";
  s << "<text x=\"" << L - 5 << "\" y=\"" << T + 10 << "\" text-anchor=\"end\">" << format_double("%.4g", y1) << "</text>\n";
  s << "<text x=\"14\" y=\"" << (T + H - B) / 2 << "\" text-anchor=\"middle\" transform=\"rotate(-90 14 " << (T + H - B) / 2
    << ")\">" << ylabel << "</text>\n";
  for (std::size_t i = 0; i < x.size(); ++i)
    s << "<circle cx=\"" << format_double("%.2f", px(x[i])) << "\" cy=\"" << format_double("%.2f", py(y[i]))
      << "\" r=\"3\" fill=\"#1f77b4\" fill-opacity=\"0.7\"/>\n";
  s << "</svg>\n";
  return s.str();
}

}  // namespace

std::string file_hash(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError(path + ": cannot read");
  std::uint64_t h = 1469598103934665603ull;
  char buf[1 << 16];
  while (f) {
    f.read(buf, sizeof buf);
    for (std::streamsize i = 0; i < f.gcount(); ++i) {
      h ^= static_cast<unsigned char>(buf[i]);
      h *= 1099511628211ull;
    }
  }
  char out[20];
  std::snprintf(out, sizeof out, "%016llx", static_cast<unsigned long long>(h));
  return out;
}

void open_sweep_dir(const fs::path& dir, const nlohmann::json& identity, const nlohmann::json& record) {
  const fs::path record_path = dir / "sweep.json";
  if (fs::exists(record_path)) {
    nlohmann::json old;
    try {
      std::ifstream f(record_path);
      old = nlohmann::json::parse(f);
    } catch (const std::exception&) {
      throw InputError(record_path.string() + ": unreadable; not a sweep folder (use another -o)");
    }
    std::string differs;
    const nlohmann::json recorded = old.value("identity", nlohmann::json::object());
    for (const auto& [key, value] : identity.items())
      if (recorded.value(key, nlohmann::json()) != value) differs += (differs.empty() ? "" : ", ") + key;
    for (const auto& [key, value] : recorded.items())
      if (!identity.contains(key)) differs += (differs.empty() ? "" : ", ") + key;
    if (!differs.empty())
      throw InputError(dir.string() + " holds a sweep made with another " + differs +
                       " (sweep.json); use another -o, or remove the folder to start over");
    return;
  }
  if (fs::exists(dir) && !fs::is_directory(dir)) throw OutputError(dir.string() + ": exists and is not a folder");
  if (fs::exists(dir) && !fs::is_empty(dir))
    throw InputError(dir.string() + ": exists, is not empty and is not a sweep folder (no sweep.json)");
  std::error_code ec;
  fs::create_directories(dir / "samples", ec);
  if (ec) throw OutputError(dir.string() + ": cannot create: " + ec.message());
  nlohmann::json r = record;
  r["identity"] = identity;
  write_atomically(record_path, r.dump(2) + "\n");
}

std::vector<int> finished_samples(const fs::path& dir) {
  std::vector<int> out;
  if (!fs::exists(dir / "samples")) return out;
  for (const auto& e : fs::directory_iterator(dir / "samples")) {
    const fs::path p = e.path();
    if (p.extension() != ".json") continue;
    try {
      std::ifstream f(p);
      const nlohmann::json j = nlohmann::json::parse(f);
      if (j.value("converged", false)) out.push_back(j["index"].get<int>());
    } catch (const std::exception&) {
      // A sample file is renamed into place whole; an unreadable one is run again.
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::map<int, std::vector<Eigen::Vector3d>> saved_fields(const fs::path& dir, const std::vector<int>& indices,
                                                          std::size_t nodes) {
  std::map<int, std::vector<Eigen::Vector3d>> out;
  for (int i : indices) {
    std::ifstream f(dir / "samples" / (sample_name(i) + ".u"), std::ios::binary);
    if (!f) continue;
    std::vector<Eigen::Vector3d> u(nodes);
    f.read(reinterpret_cast<char*>(u.data()), static_cast<std::streamsize>(nodes * sizeof(Eigen::Vector3d)));
    if (f.gcount() == static_cast<std::streamsize>(nodes * sizeof(Eigen::Vector3d))) out[i] = std::move(u);
  }
  return out;
}

void write_sample(const fs::path& dir, const Model& base, const JobConfig& config, const SweepSpec& spec,
                  const SweepLandmarks& landmarks, const SweepSample& sample, const SampleOutcome& outcome) {
  const std::string name = sample_name(sample.index);
  if (outcome.converged) {
    std::string bytes(reinterpret_cast<const char*>(outcome.displacements_mm.data()),
                      outcome.displacements_mm.size() * sizeof(Eigen::Vector3d));
    write_atomically(dir / "samples" / (name + ".u"), bytes);
    Model m;
    bool built = false;
    if (spec.save_fields || !spec.exports.empty()) {
      m = sample_model(base, spec, sample);
      built = true;
    }
    if (spec.save_fields && built) {
      fs::create_directories(dir / "fields");
      ModelVtuData d;
      VtuArray u{"displacement", 3, {"x", "y", "z"}, {}};
      for (const Eigen::Vector3d& v : outcome.displacements_mm) u.values.insert(u.values.end(), v.data(), v.data() + 3);
      d.point_data.push_back(std::move(u));
      d.string_fields = {{"displacement_unit", {"mm"}}};
      const fs::path tmp = dir / "fields" / (name + ".tmp.vtu");
      write_model_vtu(m, tmp.string(), d);
      fs::rename(tmp, dir / "fields" / (name + ".vtu"));
    }
    for (const std::string& f : spec.exports) {
      const ExportFormat& format = export_format_named(f);
      const fs::path folder = dir / "models" / name;
      fs::create_directories(folder);
      const std::string ext = fs::path(format.default_file).extension().string();
      export_model(m, format, (folder / ("model" + ext)).string(), config.exports);
    }
  }
  nlohmann::json values = nlohmann::json::object(), tissues = nlohmann::json::array();
  for (std::size_t i = 0; i < spec.parameters.size(); ++i) values[spec.parameters[i].path] = sample.values[i];
  for (const TissueMotion& t : outcome.tissues)
    tissues.push_back({{"name", t.name},
                       {"mean_displacement_mm", vec_json(t.mean_displacement_mm)},
                       {"mean_displacement_magnitude_mm", t.mean_displacement_mm.norm()}});
  nlohmann::json points = nlohmann::json::array();
  if (outcome.converged)
    for (std::size_t i = 0; i < landmarks.points.size(); ++i) {
      const Eigen::Vector3d u = landmark_position(landmarks.where[i], outcome.displacements_mm);
      points.push_back({{"name", landmarks.points[i].name},
                        {"position_mm", vec_json(landmarks.points[i].position_mm + u)},
                        {"displacement_mm", u.norm()}});
    }
  const nlohmann::json j = {{"index", sample.index},
                            {"landmarks", points},
                            {"group", sample.group},
                            {"base", sample.base},
                            {"values", values},
                            {"unit", sample.unit},
                            {"converged", outcome.converged},
                            {"message", outcome.message},
                            {"max_displacement_mm", outcome.max_displacement_mm},
                            {"tissues", tissues},
                            {"reaction_vs_weight_rel", outcome.reaction_vs_weight_rel},
                            {"increments", outcome.increments},
                            {"newton_iterations", outcome.newton_iterations},
                            {"warm_from", outcome.warm_from},
                            {"seconds", outcome.seconds}};
  require_finite(j, "sample " + std::to_string(sample.index));
  write_atomically(dir / "samples" / (name + ".json"), j.dump() + "\n");
}

int write_results(const fs::path& dir, const Model& base, const SweepSpec& spec, const SweepLandmarks& landmarks,
                  const std::vector<SweepSample>& design, RunReport* report) {
  std::vector<nlohmann::json> rows;
  int missing = 0;
  for (const SweepSample& s : design) {
    std::ifstream f(dir / "samples" / (sample_name(s.index) + ".json"));
    if (!f) {
      ++missing;
      continue;
    }
    rows.push_back(nlohmann::json::parse(f));
  }
  // results.csv: the deterministic outputs (no wall times: those are in results.jsonl).
  std::string csv = "sample,group";
  for (const SweepParameter& p : spec.parameters) csv += "," + p.path;
  csv += ",converged,max_displacement_mm";
  const bool has_tumour = [&] {
    for (const std::string& n : base.tissue_names)
      if (n == "tumor" || n == "tumour") return true;
    return false;
  }();
  if (has_tumour) csv += ",tumour_displacement_x_mm,tumour_displacement_y_mm,tumour_displacement_z_mm,tumour_displacement_mm";
  for (const std::string& n : base.tissue_names)
    csv += "," + n + "_mean_displacement_x_mm," + n + "_mean_displacement_y_mm," + n + "_mean_displacement_z_mm," + n +
           "_mean_displacement_mm";
  for (const Landmark& p : landmarks.points)
    csv += "," + p.name + "_x_mm," + p.name + "_y_mm," + p.name + "_z_mm," + p.name + "_displacement_mm";
  csv += ",reaction_vs_weight_rel,increments,newton_iterations,warm_from,message\n";
  std::string jsonl;
  for (const nlohmann::json& r : rows) {
    csv += std::to_string(r["index"].get<int>()) + "," + r["group"].get<std::string>();
    for (const SweepParameter& p : spec.parameters) csv += "," + number(r["values"][p.path].get<double>());
    const bool ok = r["converged"].get<bool>();
    csv += std::string(",") + (ok ? "true" : "false") + "," + (ok ? number(r["max_displacement_mm"].get<double>()) : "");
    auto tissue_cols = [&](const std::string& name) {
      for (const auto& t : r["tissues"])
        if (t["name"] == name) {
          const auto& v = t["mean_displacement_mm"];
          return "," + number(v[0].get<double>()) + "," + number(v[1].get<double>()) + "," + number(v[2].get<double>()) +
                 "," + number(t["mean_displacement_magnitude_mm"].get<double>());
        }
      return std::string(",,,,");
    };
    if (has_tumour) {
      std::string t;
      for (const std::string& n : base.tissue_names)
        if (n == "tumor" || n == "tumour") t = n;
      csv += tissue_cols(t);
    }
    for (const std::string& n : base.tissue_names) csv += tissue_cols(n);
    for (const Landmark& p : landmarks.points) {
      std::string cols = ",,,,";
      for (const auto& l : r["landmarks"])
        if (l["name"] == p.name) {
          const auto& x = l["position_mm"];
          cols = "," + number(x[0].get<double>()) + "," + number(x[1].get<double>()) + "," + number(x[2].get<double>()) +
                 "," + number(l["displacement_mm"].get<double>());
        }
      csv += cols;
    }
    csv += "," + (ok ? number(r["reaction_vs_weight_rel"].get<double>()) : std::string()) + "," +
           std::to_string(r["increments"].get<int>()) + "," + std::to_string(r["newton_iterations"].get<int>()) + "," +
           std::to_string(r["warm_from"].get<int>()) + "," + csv_text(r["message"].get<std::string>()) + "\n";
    jsonl += r.dump() + "\n";
  }
  write_atomically(dir / "results.csv", csv);
  write_atomically(dir / "results.jsonl", jsonl);

  // Summary over the converged samples.
  std::vector<const nlohmann::json*> ok;
  for (const nlohmann::json& r : rows)
    if (r["converged"].get<bool>()) ok.push_back(&r);
  const std::size_t d = spec.parameters.size();
  nlohmann::json outputs = nlohmann::json::array();
  std::string text = "sweep: " + std::to_string(rows.size()) + " of " + std::to_string(design.size()) + " samples, " +
                     std::to_string(ok.size()) + " converged (design " + design_name(spec.design) + ")\n";
  fs::create_directories(dir / "plots");
  if (!ok.empty()) {
    const auto names = scalar_outputs(*ok[0]);
    for (std::size_t o = 0; o < names.size(); ++o) {
      const std::string& name = names[o].first;
      Eigen::VectorXd y(static_cast<Eigen::Index>(ok.size()));
      Eigen::MatrixXd x(static_cast<Eigen::Index>(ok.size()), static_cast<Eigen::Index>(d));
      for (std::size_t i = 0; i < ok.size(); ++i) {
        y[i] = scalar_outputs(*ok[i])[o].second;
        for (std::size_t k = 0; k < d; ++k) x(i, k) = (*ok[i])["unit"][k].get<double>();
      }
      Eigen::Index imin, imax;
      y.minCoeff(&imin);
      y.maxCoeff(&imax);
      nlohmann::json j = {{"name", name},
                          {"min", y[imin]},
                          {"min_sample", (*ok[imin])["index"]},
                          {"max", y[imax]},
                          {"max_sample", (*ok[imax])["index"]},
                          {"mean", y.mean()}};
      text += "\n" + name + ": " + format_double("%.6g", y[imin]) + " (sample " +
              std::to_string((*ok[imin])["index"].get<int>()) + ") to " + format_double("%.6g", y[imax]) + " (sample " +
              std::to_string((*ok[imax])["index"].get<int>()) + ")\n";
      if (ok.size() > d + 1) {
        const RegressionSensitivity src = standardised_regression(x, y);
        nlohmann::json per = nlohmann::json::object();
        for (std::size_t k = 0; k < d; ++k) per[spec.parameters[k].path] = src.src[k];
        j["src"] = per;
        j["src_r_squared"] = src.r_squared;
        text += "  standardised regression coefficients (on the design coordinates; R^2 " +
                format_double("%.3f", src.r_squared) + "):";
        for (std::size_t k = 0; k < d; ++k)
          text += " " + spec.parameters[k].path + " " + format_double("%+.3f", src.src[k]);
        text += "\n";
      }
      if (spec.design == DesignType::Sobol) {
        std::map<int, std::map<std::string, double>> bases;
        for (std::size_t i = 0; i < ok.size(); ++i) bases[(*ok[i])["base"].get<int>()][(*ok[i])["group"].get<std::string>()] = y[i];
        std::vector<int> complete;
        for (const auto& [b, g] : bases)
          if (g.size() == d + 2) complete.push_back(b);
        if (complete.size() >= 2) {
          const Eigen::Index n = static_cast<Eigen::Index>(complete.size());
          Eigen::VectorXd fa(n), fb(n);
          Eigen::MatrixXd fab(n, static_cast<Eigen::Index>(d));
          for (Eigen::Index i = 0; i < n; ++i) {
            const auto& g = bases[complete[i]];
            fa[i] = g.at("A");
            fb[i] = g.at("B");
            for (std::size_t k = 0; k < d; ++k) fab(i, k) = g.at("AB" + std::to_string(k + 1));
          }
          const SobolIndices si = sobol_indices(fa, fb, fab);
          nlohmann::json first = nlohmann::json::object(), total = nlohmann::json::object();
          text += "  Sobol' indices (" + std::to_string(n) + " complete base points): first / total";
          for (std::size_t k = 0; k < d; ++k) {
            first[spec.parameters[k].path] = si.first[k];
            total[spec.parameters[k].path] = si.total[k];
            text += " " + spec.parameters[k].path + " " + format_double("%.3f", si.first[k]) + " / " +
                    format_double("%.3f", si.total[k]);
          }
          text += "\n";
          j["sobol_first"] = first;
          j["sobol_total"] = total;
          j["sobol_base_points"] = n;
        }
      }
      for (std::size_t k = 0; k < d; ++k) {
        std::vector<double> xs, ys;
        for (std::size_t i = 0; i < ok.size(); ++i) {
          xs.push_back((*ok[i])["values"][spec.parameters[k].path].get<double>());
          ys.push_back(y[i]);
        }
        std::string file = name + "__" + spec.parameters[k].path + ".svg";
        write_atomically(dir / "plots" / file,
                         scatter_svg(name + " against " + spec.parameters[k].path, spec.parameters[k].path, name, xs, ys,
                                     spec.parameters[k].scale == ParameterScale::Log));
      }
      outputs.push_back(j);
    }
  }
  nlohmann::json failed = nlohmann::json::array();
  for (const nlohmann::json& r : rows)
    if (!r["converged"].get<bool>()) failed.push_back({{"sample", r["index"]}, {"reason", r["message"]}});
  if (!failed.empty()) text += "\nfailed samples: " + std::to_string(failed.size()) + " (results.csv says why)\n";
  const nlohmann::json summary = {{"samples", design.size()},
                                  {"finished", rows.size()},
                                  {"converged", ok.size()},
                                  {"missing", missing},
                                  {"design", design_name(spec.design)},
                                  {"outputs", outputs},
                                  {"failed", failed},
                                  {"sensitivity_note",
                                   "src: standardised regression coefficients on each parameter's design coordinate "
                                   "(log scale: of the logarithm); sobol_first / sobol_total: Saltelli 2010 / "
                                   "Jansen 1999 estimators over the complete base points"}};
  write_atomically(dir / "summary.json", summary.dump(2) + "\n");
  write_atomically(dir / "summary.txt", text);
  if (report && report->enabled()) {
    report->add_mesh_view(corner_mesh(base));
    report->add_sweep_summary(summary);
    report->add_table("Sweep summary (summary.txt)", text);
    write_atomically(dir / "report.html", report->html());
  }
  return missing;
}

}  // namespace tissuemesh::app
