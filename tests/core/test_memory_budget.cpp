// Up-front memory refusal (core/memory_budget.h): overflow-checked sizes, the user's cap, messages.
#include "core/errors.h"
#include "core/memory_budget.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <limits>
#include <string>

using namespace tissuemesh;

namespace {

// Sets TISSUEMESH_MEMORY_MB for one test and restores the previous value.
class MemoryCap {
 public:
  explicit MemoryCap(const char* mib) {
    if (const char* old = std::getenv("TISSUEMESH_MEMORY_MB")) old_ = old, had_ = true;
    setenv("TISSUEMESH_MEMORY_MB", mib, 1);
  }
  ~MemoryCap() { had_ ? setenv("TISSUEMESH_MEMORY_MB", old_.c_str(), 1) : unsetenv("TISSUEMESH_MEMORY_MB"); }

 private:
  std::string old_;
  bool had_ = false;
};

}  // namespace

TEST(MemoryBudget, CheckedMultiplyRefusesOverflowAndNamesTheFactors) {
  EXPECT_EQ(checked_multiply(1u << 20, 1u << 20, "x"), std::uint64_t{1} << 40);
  const std::uint64_t big = std::uint64_t{1} << 40;
  try {
    checked_multiply(big, big, "img.nrrd: sizes");
    FAIL() << "no error for 2^80";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("img.nrrd: sizes: 1099511627776 x 1099511627776 overflows 64 bits"),
              std::string::npos) << e.what();
  }
}

TEST(MemoryBudget, TheUserCapBoundsWhatIsAvailable) {
  const MemoryCap cap("64");
  EXPECT_EQ(available_memory_bytes(), std::uint64_t{64} << 20);
  EXPECT_NO_THROW(require_memory(std::uint64_t{63} << 20, "job", "63 MiB of voxels"));
  try {
    require_memory(std::uint64_t{65} << 20, "labels.nii.gz: reading", "68157440 voxels of 1 byte");
    FAIL() << "65 MiB accepted under a 64 MiB cap";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("labels.nii.gz: reading needs about 65.0 MiB (68157440 voxels of 1 byte)"), std::string::npos) << m;
    EXPECT_NE(m.find("64.0 MiB available"), std::string::npos) << m;
  }
}

TEST(MemoryBudget, AMalformedCapIsBadInput) {
  const MemoryCap cap("lots");
  EXPECT_THROW(available_memory_bytes(), InputError);
}

TEST(MemoryBudget, WithoutCapTheMachineLimitsIt) {
  // /proc/meminfo exists on every machine the tests run on: the estimate is finite and nonzero.
  const std::uint64_t available = available_memory_bytes();
  EXPECT_GT(available, 0u);
  EXPECT_LT(available, std::numeric_limits<std::uint64_t>::max());
  EXPECT_THROW(require_memory(std::numeric_limits<std::uint64_t>::max(), "x", "y"), InputError);
}

TEST(MemoryBudget, FormatBytes) {
  EXPECT_EQ(format_bytes(512), "512 bytes");
  EXPECT_EQ(format_bytes(1536), "1.5 KiB");
  EXPECT_EQ(format_bytes(std::uint64_t{3} << 40), "3.0 TiB");
}
