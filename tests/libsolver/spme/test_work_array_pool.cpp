#include <gtest/gtest.h>

#include "libsolver/spme/work_array_pool.h"

using namespace rbcflow;

namespace {
constexpr std::size_t kComplex = sizeof(fftw_complex);
}

TEST(WorkArrayPool, FreesWhatComesBackUnlessKeeping) {
  WorkArrayPool pool;
  EXPECT_FALSE(pool.keeping());
  pool.give_back(pool.take(1000));
  EXPECT_EQ(pool.waiting_bytes(), 0u);
  pool.keep(true);
  pool.give_back(pool.take(1000));
  EXPECT_EQ(pool.waiting_bytes(), 1000 * kComplex);
  pool.keep(false);
  EXPECT_EQ(pool.waiting_bytes(), 0u);
}

// One array waits, the largest given back: the smaller is freed; a request it fits gets the
// same memory, a larger one frees it before allocating.
TEST(WorkArrayPool, KeepsTheLargestArrayGivenBack) {
  WorkArrayPool pool;
  pool.keep(true);
  FftwBuffer<fftw_complex> large = pool.take(3000), small = pool.take(1000);
  const fftw_complex* large_data = large.data();
  pool.give_back(std::move(small));
  EXPECT_EQ(pool.waiting_bytes(), 1000 * kComplex);
  pool.give_back(std::move(large));
  EXPECT_EQ(pool.waiting_bytes(), 3000 * kComplex);
  pool.give_back(pool.take(2000));  // the waiting array, handed out and given back
  FftwBuffer<fftw_complex> again = pool.take(900);
  EXPECT_EQ(again.data(), large_data);
  EXPECT_EQ(again.size(), 3000u);
  EXPECT_EQ(pool.waiting_bytes(), 0u);
  pool.give_back(std::move(again));
  FftwBuffer<fftw_complex> larger = pool.take(5000);  // the waiting 3000 is freed, not kept beside it
  EXPECT_EQ(larger.size(), 5000u);
  EXPECT_EQ(pool.waiting_bytes(), 0u);
  pool.give_back(pool.take(100));
  EXPECT_EQ(pool.waiting_bytes(), 100 * kComplex);
  pool.give_back(std::move(larger));
  EXPECT_EQ(pool.waiting_bytes(), 5000 * kComplex);
}

TEST(WorkArrayPool, AWorkArrayGoesBackToItsPool) {
  WorkArrayPool pool;
  pool.keep(true);
  const fftw_complex* data = nullptr;
  {
    WorkArray a(pool.take(64), &pool);
    data = a.data();
    WorkArray moved(std::move(a));  // given back once, by the one that holds it
    EXPECT_EQ(moved.data(), data);
  }
  EXPECT_EQ(pool.waiting_bytes(), 64 * kComplex);
  EXPECT_EQ(pool.take(64).data(), data);
}
