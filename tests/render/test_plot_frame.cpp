// The chart frame of `rlrun plot` and `rlrun tune report` (src/rlrun/render/plot_frame.hpp).
#include <catch2/catch.hpp>

#include <fstream>

#include "rlrun/core/errors.hpp"
#include "rlrun/core/private_temp_dir.hpp"
#include "rlrun/render/plot_frame.hpp"

TEST_CASE("Chart ticks step by 1, 2 or 5 and their labels shorten round thousands", "[render]") {
  CHECK(rlrun::nice_ticks(0, 10) == std::vector<double>{0, 2, 4, 6, 8, 10});
  CHECK(rlrun::nice_ticks(0, 100000).size() == 6);
  const std::vector<double> small = rlrun::nice_ticks(-0.3, 0.3);
  REQUIRE(small.size() == 7);
  for (size_t i = 0; i < small.size(); ++i) CHECK(small[i] == Approx(-0.3 + 0.1 * i).margin(1e-12));
  CHECK(rlrun::tick_label(20000, 10000) == "20k");
  CHECK(rlrun::tick_label(1500000, 500000) == "1.5M");
  CHECK(rlrun::tick_label(1e-17, 0.1) == "0");
  CHECK(rlrun::tick_label(0.25, 0.05) == "0.25");
}

TEST_CASE("A chart canvas writes PNG or SVG by the file's extension", "[render]") {
  rlrun::PrivateTempDir dir("rlrun_test_plot_frame_");
  for (const std::string name : {"a.png", "a.svg"}) {
    rlrun::PlotCanvas canvas(dir.file(name), 200, 100);
    rlrun::PlotArea area;
    area.left = 30, area.top = 10, area.width = 160, area.height = 60;
    rlrun::draw_grid(canvas.cr(), area, {0, 0.5, 1}, {0, 1});
    rlrun::draw_titles(canvas.cr(), area, 100, "x", "y", "title");
    canvas.save();
    std::ifstream in(dir.file(name), std::ios::binary);
    std::string head(4, '\0');
    in.read(head.data(), 4);
    CHECK(head == (name == "a.png" ? std::string("\x89PNG") : std::string("<?xm")));
  }
  CHECK(rlrun::is_plot_extension("x.svg"));
  CHECK(!rlrun::is_plot_extension("x.pdf"));
  CHECK_THROWS_AS(rlrun::PlotCanvas(dir.file("a.pdf"), 10, 10), rlrun::UsageError);
  CHECK(rlrun::text_width("wide text", 12) > rlrun::text_width("w", 12));
}
