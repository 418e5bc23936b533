// machine_reference: a fixed workload that does not depend on tissuemesh's code, timed by the
// bench scripts in the same run as tissuemesh, so that a time can be given as a ratio to it as
// well as in seconds. Instances of the same machine kind differ in speed by up to about 2.5x
// (bench/RESULTS.md), which an absolute time alone cannot tell from a change of the code.
//
// The workload: TetGen 1.5 (the Debian library, a fixed version) builds the Delaunay
// tetrahedralisation of 200,000 points from a fixed linear congruential sequence in a unit cube,
// on one thread. Like the remesher it is geometric predicates and pointer-chasing over a mesh of a
// few hundred thousand elements. Prints the wall time in seconds of that one call.
//
// Usage: machine_reference (no arguments).
#define TETLIBRARY
#include <tetgen.h>

#include <chrono>
#include <cstdint>
#include <cstdio>

int main() {
  constexpr int kPoints = 200000;
  tetgenio in, out;
  in.numberofpoints = kPoints;
  in.pointlist = new REAL[3 * kPoints];
  std::uint64_t state = 0x9E3779B97F4A7C15ULL;  // any fixed seed: the same points on every run
  for (int i = 0; i < 3 * kPoints; ++i) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;  // Knuth's MMIX LCG
    in.pointlist[i] = static_cast<double>(state >> 11) / static_cast<double>(std::uint64_t(1) << 53);
  }
  char switches[] = "Q";  // Delaunay tetrahedralisation of the points, quiet
  const auto start = std::chrono::steady_clock::now();
  tetrahedralize(switches, &in, &out);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (out.numberoftetrahedra <= 0) {
    std::fprintf(stderr, "machine_reference: TetGen returned no tetrahedra\n");
    return 1;
  }
  std::printf("%.4f\n", seconds);
  return 0;
}
