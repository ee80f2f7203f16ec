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

// The smallest waiting array that fits is handed out again, the same memory; a request no
// waiting array fits frees them all before it allocates, so that what waits never exceeds what
// was live at once.
TEST(WorkArrayPool, HandsOutTheSmallestWaitingArrayThatFits) {
  WorkArrayPool pool;
  pool.keep(true);
  FftwBuffer<fftw_complex> large = pool.take(3000), small = pool.take(1000);
  const fftw_complex *large_data = large.data(), *small_data = small.data();
  pool.give_back(std::move(large));
  pool.give_back(std::move(small));
  EXPECT_EQ(pool.waiting_bytes(), 4000 * kComplex);

  FftwBuffer<fftw_complex> a = pool.take(900);
  EXPECT_EQ(a.data(), small_data);
  EXPECT_EQ(a.size(), 1000u);
  FftwBuffer<fftw_complex> b = pool.take(1200);
  EXPECT_EQ(b.data(), large_data);
  EXPECT_EQ(pool.waiting_bytes(), 0u);
  pool.give_back(std::move(a));
  FftwBuffer<fftw_complex> c = pool.take(5000);  // the waiting 1000 is freed, not kept beside it
  EXPECT_EQ(c.size(), 5000u);
  EXPECT_EQ(pool.waiting_bytes(), 0u);
  pool.give_back(std::move(b));
  pool.give_back(std::move(c));
  EXPECT_EQ(pool.waiting_bytes(), 8000 * kComplex);
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
