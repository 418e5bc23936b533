#include "workflows/sweep_design.h"

#include "core/errors.h"
#include "workflows/sobol_sequence.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <sstream>

namespace tissuemesh {

namespace {

constexpr double kMaxSamples = 1e6;

/// values[i] of a tied parameter holds its ratio on entry (or is computed from `unit` by the
/// caller); multiplies it by its target's value.
void resolve_ties(const SweepSpec& spec, std::vector<double>& values);

double value_at(const SweepParameter& p, double u) {
  u = std::clamp(u, 0.0, 1.0);
  if (!p.has_range) {
    const std::size_t k = p.values.size();
    return p.values[std::min(k - 1, static_cast<std::size_t>(std::floor(u * static_cast<double>(k))))];
  }
  if (u == 0.0) return p.lo;  // the range's ends exactly, whatever the scale's round-off
  if (u == 1.0) return p.hi;
  if (p.scale == ParameterScale::Log) return std::exp(std::log(p.lo) + u * (std::log(p.hi) - std::log(p.lo)));
  return p.lo + u * (p.hi - p.lo);
}

void resolve_ties(const SweepSpec& spec, std::vector<double>& values) {
  for (std::size_t i = 0; i < spec.parameters.size(); ++i) {
    const SweepParameter& p = spec.parameters[i];
    if (p.ratio_to.empty()) continue;
    std::size_t target = 0;
    while (spec.parameters[target].path != p.ratio_to) ++target;
    values[i] *= values[target];
  }
}

/// Values of every parameter from its unit coordinate (one per parameter): a tied parameter's
/// coordinate gives its ratio, times its target's value.
SweepSample sample_from_unit(const SweepSpec& spec, std::vector<double> unit) {
  SweepSample s;
  s.values.assign(spec.parameters.size(), 0.0);
  for (std::size_t i = 0; i < spec.parameters.size(); ++i) s.values[i] = value_at(spec.parameters[i], unit[i]);
  resolve_ties(spec, s.values);
  s.unit = std::move(unit);
  return s;
}

std::vector<SweepSample> grid(const SweepSpec& spec, const std::vector<int>& free) {
  std::vector<std::vector<double>> axes;
  double total = 1.0;
  for (int i : free) {
    const SweepParameter& p = spec.parameters[i];
    std::vector<double> u;
    const int n = p.has_range ? spec.levels : static_cast<int>(p.values.size());
    for (int k = 0; k < n; ++k) u.push_back(n == 1 ? 0.5 : p.has_range ? double(k) / (n - 1) : (k + 0.5) / n);
    total *= n;
    axes.push_back(u);
  }
  if (total > kMaxSamples) throw InputError(spec.source + ": the grid has " + std::to_string(total) + " samples (at most 1,000,000)");
  std::vector<SweepSample> out;
  std::vector<std::size_t> at(axes.size(), 0);
  for (std::size_t n = 0; n < static_cast<std::size_t>(total); ++n) {
    std::vector<double> unit(axes.size());
    for (std::size_t k = 0; k < axes.size(); ++k) unit[k] = axes[k][at[k]];
    out.push_back(sample_from_unit(spec, unit));
    for (std::size_t k = axes.size(); k-- > 0;) {  // the last parameter varies fastest
      if (++at[k] < axes[k].size()) break;
      at[k] = 0;
    }
  }
  return out;
}

std::vector<SweepSample> lhs(const SweepSpec& spec, const std::vector<int>& free) {
  const int n = spec.samples;
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<std::vector<double>> u(free.size(), std::vector<double>(n));
  for (std::size_t k = 0; k < free.size(); ++k) {
    std::vector<int> strata(n);
    std::iota(strata.begin(), strata.end(), 0);
    std::shuffle(strata.begin(), strata.end(), rng);
    for (int i = 0; i < n; ++i) u[k][i] = (strata[i] + uniform(rng)) / n;
  }
  std::vector<SweepSample> out;
  for (int i = 0; i < n; ++i) {
    std::vector<double> unit(free.size());
    for (std::size_t k = 0; k < free.size(); ++k) unit[k] = u[k][i];
    out.push_back(sample_from_unit(spec, unit));
  }
  return out;
}

std::vector<SweepSample> saltelli(const SweepSpec& spec, const std::vector<int>& free) {
  const int d = static_cast<int>(free.size()), n = spec.samples;
  if (2 * d > kMaxSobolDimensions)
    throw InputError(spec.source + ": a sobol design takes at most " + std::to_string(kMaxSobolDimensions / 2) +
                     " free parameters (it has " + std::to_string(d) + ")");
  if (double(n) * (d + 2) > kMaxSamples) throw InputError(spec.source + ": the sobol design has over 1,000,000 samples");
  const std::vector<double> p = sobol_points(n, 2 * d, spec.seed);
  std::vector<SweepSample> out;
  for (int i = 0; i < n; ++i) {
    std::vector<double> a(d), b(d);
    for (int k = 0; k < d; ++k) {
      a[k] = p[static_cast<std::size_t>(i) * 2 * d + k];
      b[k] = p[static_cast<std::size_t>(i) * 2 * d + d + k];
    }
    auto add = [&](const std::vector<double>& unit, const std::string& group) {
      SweepSample s = sample_from_unit(spec, unit);
      s.group = group;
      s.base = i;
      out.push_back(std::move(s));
    };
    add(a, "A");
    add(b, "B");
    for (int j = 0; j < d; ++j) {
      std::vector<double> ab = a;
      ab[j] = b[j];
      add(ab, "AB" + std::to_string(j + 1));
    }
  }
  return out;
}

std::vector<SweepSample> table(const SweepSpec& spec, const std::vector<int>& free) {
  std::ifstream in(spec.table_file);
  if (!in) throw InputError(spec.table_file + ": cannot open the design table");
  std::string line;
  auto split = [](const std::string& l) {
    std::vector<std::string> f;
    std::stringstream ss(l);
    std::string x;
    while (std::getline(ss, x, ',')) {
      const auto b = x.find_first_not_of(" \t\r"), e = x.find_last_not_of(" \t\r");
      f.push_back(b == std::string::npos ? "" : x.substr(b, e - b + 1));
    }
    return f;
  };
  if (!std::getline(in, line)) throw InputError(spec.table_file + ": empty design table");
  const std::vector<std::string> header = split(line);
  std::vector<int> column(free.size(), -1);
  for (std::size_t k = 0; k < free.size(); ++k) {
    for (std::size_t c = 0; c < header.size(); ++c)
      if (header[c] == spec.parameters[free[k]].path) column[k] = static_cast<int>(c);
    if (column[k] < 0)
      throw InputError(spec.table_file + ":1: no column for parameter '" + spec.parameters[free[k]].path + "'");
  }
  std::vector<SweepSample> out;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> f = split(line);
    SweepSample s;
    s.values.assign(spec.parameters.size(), 0.0);
    s.unit.assign(free.size(), 0.0);
    for (std::size_t k = 0; k < free.size(); ++k) {
      double v = 0.0;
      std::istringstream is(static_cast<std::size_t>(column[k]) < f.size() ? f[column[k]] : "");
      if (!(is >> v) || !std::isfinite(v))
        throw InputError(spec.table_file + ":" + std::to_string(number) + ": '" + spec.parameters[free[k]].path +
                         "' is not a number");
      s.values[free[k]] = v;  // a tied parameter's column holds its ratio
      const SweepParameter& p = spec.parameters[free[k]];
      const double lo = p.has_range ? p.lo : *std::min_element(p.values.begin(), p.values.end());
      const double hi = p.has_range ? p.hi : *std::max_element(p.values.begin(), p.values.end());
      s.unit[k] = hi > lo ? (v - lo) / (hi - lo) : 0.5;  // distances only
    }
    resolve_ties(spec, s.values);
    out.push_back(std::move(s));
  }
  if (out.empty()) throw InputError(spec.table_file + ": no sample rows");
  return out;
}

}  // namespace

std::vector<SweepSample> make_design(const SweepSpec& spec) {
  std::vector<int> free(spec.parameters.size());  // every parameter is a dimension (a tie: its ratio)
  std::iota(free.begin(), free.end(), 0);
  std::vector<SweepSample> out;
  switch (spec.design) {
    case DesignType::Grid: out = grid(spec, free); break;
    case DesignType::Lhs: out = lhs(spec, free); break;
    case DesignType::Sobol: out = saltelli(spec, free); break;
    case DesignType::Table: out = table(spec, free); break;
  }
  for (std::size_t i = 0; i < out.size(); ++i) out[i].index = static_cast<int>(i);
  return out;
}

}  // namespace tissuemesh
