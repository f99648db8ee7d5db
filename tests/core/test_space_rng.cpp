#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "rlrun/rng.hpp"
#include "rlrun/space.hpp"

using namespace rlrun;

TEST_CASE("spaces: contains, sample and describe", "[core][space]") {
  Rng rng(1);
  const Space box = Space::box({-1.0f, 0.0f}, {1.0f, 2.0f});
  CHECK(box.flat_dim() == 2);
  CHECK(box.describe() == "Box([-1.0 0.0], [1.0 2.0], (2,), float32)");
  CHECK(Space::box(-2.0f, 2.0f, {1}).describe() == "Box(-2.0, 2.0, (1,), float32)");
  std::vector<float> x(2);
  for (int i = 0; i < 200; ++i) {
    box.sample(rng, x);
    CHECK(box.contains(x));
  }
  CHECK(!box.contains(std::vector<float>{1.5f, 0.0f}));
  CHECK(!box.contains(std::vector<float>{0.0f}));
  CHECK(!box.contains(std::vector<float>{NAN, 0.0f}));

  const Space d = Space::discrete(3);
  CHECK(d.describe() == "Discrete(3)");
  CHECK(d.flat_dim() == 1);
  std::vector<float> a(1);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < 3000; ++i) {
    d.sample(rng, a);
    REQUIRE(d.contains(a));
    ++counts[static_cast<int>(a[0])];
  }
  for (int c : counts) CHECK(c == Approx(1000).margin(120));
  CHECK(!d.contains(std::vector<float>{3.0f}));
  CHECK(!d.contains(std::vector<float>{0.5f}));
  CHECK(Space::discrete(3, 1).describe() == "Discrete(3, start=1)");

  const Space md = Space::multi_discrete({5, 5});
  CHECK(md.describe() == "MultiDiscrete([5 5])");
  CHECK(md.contains(std::vector<float>{4.0f, 0.0f}));
  CHECK(!md.contains(std::vector<float>{5.0f, 0.0f}));
  const Space mb = Space::multi_binary(3);
  CHECK(mb.describe() == "MultiBinary(3)");
  CHECK(mb.contains(std::vector<float>{1.0f, 0.0f, 1.0f}));
  CHECK(!mb.contains(std::vector<float>{2.0f, 0.0f, 1.0f}));

  // Unbounded dimensions sample from a normal, half-bounded from an exponential.
  const Space open = Space::box({-INFINITY, 0.0f}, {INFINITY, INFINITY});
  for (int i = 0; i < 100; ++i) {
    open.sample(rng, x);
    CHECK(open.contains(x));
  }
  CHECK_THROWS(Space::box({1.0f}, {0.0f}));
  CHECK_THROWS(Space::discrete(0));
}

TEST_CASE("rng: serialisable, reproducible, uniform", "[core][rng]") {
  Rng a(123), b(123), c(124);
  CHECK(a.next_u64() == b.next_u64());
  CHECK(a.next_u64() != c.next_u64());
  a.normal();  // leaves a cached spare normal in the state
  const Rng::State saved = a.state();
  const double n1 = a.normal(), u1 = a.uniform();
  Rng restored;
  restored.set_state(saved);
  CHECK(restored.normal() == n1);
  CHECK(restored.uniform() == u1);
  double sum = 0, sq = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double z = a.normal();
    sum += z;
    sq += z * z;
  }
  CHECK(sum / n == Approx(0.0).margin(0.03));
  CHECK(sq / n == Approx(1.0).margin(0.05));
  for (int i = 0; i < 1000; ++i) {
    const double u = a.uniform();
    REQUIRE(u >= 0.0);
    REQUIRE(u < 1.0);
    REQUIRE(a.below(7) < 7u);
  }
}

// ASan found a test sampling a 3-float Box into 4 floats: sample() read the bounds past their
// end. A span of another size than flat_dim() is refused before anything is read or written.
TEST_CASE("spaces: sample refuses a span of the wrong size", "[core][space]") {
  Rng rng(1);
  const Space box = Space::box(-1.0f, 1.0f, {3});
  std::vector<float> longer(4, 7.0f), shorter(2, 7.0f);
  CHECK_THROWS_WITH(
      box.sample(rng, longer),
      Catch::Contains("4 floats given for Box(-1.0, 1.0, (3,), float32), which has 3"));
  CHECK_THROWS_AS(box.sample(rng, shorter), std::invalid_argument);
  CHECK(longer == std::vector<float>(4, 7.0f));
  std::vector<float> none;
  CHECK_THROWS_AS(Space::discrete(3).sample(rng, none), std::invalid_argument);
  const Space dict = Space::dict({{"a", Space::box(0.0f, 1.0f, {2})}, {"b", Space::discrete(2)}});
  std::vector<float> exact(3);
  dict.sample(rng, exact);
  CHECK(dict.contains(exact));
}

TEST_CASE("spaces: a uint8 Box holds whole numbers in 0-255 (Gymnasium's Box(dtype=np.uint8))",
          "[core][space][image]") {
  const Space image = Space::image({2, 3});
  CHECK(image.is_uint8_box());
  CHECK(image.describe() == "Box(0, 255, (2, 3), uint8)");
  CHECK(Space::box(0.0f, 255.0f, {2}).describe() == "Box(0.0, 255.0, (2,), float32)");
  CHECK(image.contains(std::vector<float>{0, 1, 2, 128, 254, 255}));
  CHECK_FALSE(image.contains(std::vector<float>{0, 1, 2, 128, 254, 255.5f}));
  CHECK_FALSE(image.contains(std::vector<float>{0, 1.5f, 2, 128, 254, 255}));
  CHECK_FALSE(image == Space::box(0.0f, 255.0f, {2, 3}));
  // box.py's integer rule: floor(uniform(low, high + 1)), so both bounds come out.
  const Space narrow = Space::box(3.0f, 5.0f, {1}, BoxDtype::kUint8);
  Rng rng(7);
  std::vector<float> x(1);
  int seen[3] = {0, 0, 0};
  for (int i = 0; i < 3000; ++i) {
    narrow.sample(rng, x);
    REQUIRE(narrow.contains(x));
    ++seen[static_cast<int>(x[0]) - 3];
  }
  for (int count : seen) CHECK(count > 800);
  CHECK_THROWS_WITH(Space::box(0.0f, 256.0f, {1}, BoxDtype::kUint8), Catch::Contains("0 to 255"));
  CHECK_THROWS_WITH(Space::box(0.5f, 2.0f, {1}, BoxDtype::kUint8), Catch::Contains("whole"));
}
