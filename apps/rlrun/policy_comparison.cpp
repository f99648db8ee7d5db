#include "policy_comparison.hpp"

#include <algorithm>
#include <cstdio>

namespace rlrun::cli {

namespace {

std::string fixed(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

double mean_of(const std::vector<double>& values) {
  double sum = 0;
  for (double v : values) sum += v;
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

// The mean of metric `k` over a run's episodes (the digits print_summary uses: 3).
double metric_mean(const EvalResult& r, size_t k) {
  std::vector<double> values;
  for (const auto& episode : r.metrics)
    if (k < episode.size()) values.push_back(episode[k]);
  return mean_of(values);
}

std::string markdown(const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> width(rows.front().size(), 3);
  for (const auto& row : rows)
    for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  std::string out;
  // Appended piece by piece: `"literal" + std::string` trips GCC 12's -Wrestrict false positive.
  const auto line = [&](const std::vector<std::string>& row) {
    for (size_t c = 0; c < row.size(); ++c) {
      out += "| ";
      out += row[c];
      out.append(width[c] - row[c].size() + 1, ' ');
    }
    out += "|\n";
  };
  line(rows.front());
  for (size_t c = 0; c < width.size(); ++c) {
    out += '|';
    out.append(width[c] + 2, '-');
  }
  out += "|\n";
  for (size_t r = 1; r < rows.size(); ++r) line(rows[r]);
  return out;
}

}  // namespace

std::string comparison_table(const std::vector<std::pair<std::string, EvalResult>>& runs) {
  const bool with_success = std::any_of(
      runs.begin(), runs.end(), [](const auto& run) { return !run.second.successes.empty(); });
  const std::vector<std::string>& keys = runs.front().second.metric_keys;
  std::vector<std::vector<std::string>> rows{
      {"policy", "mean_reward", "std_reward", "mean_ep_length"}};
  if (with_success) rows.front().push_back("success_rate");
  rows.front().insert(rows.front().end(), keys.begin(), keys.end());
  for (const auto& [policy, r] : runs) {
    std::vector<std::string> row{policy, fixed(r.mean_return(), 2), fixed(r.std_return(), 2),
                                 fixed(r.mean_length(), 1)};
    if (with_success) row.push_back(r.successes.empty() ? "-" : fixed(mean_of(r.successes), 3));
    for (size_t k = 0; k < keys.size(); ++k) row.push_back(fixed(metric_mean(r, k), 3));
    rows.push_back(std::move(row));
  }
  return markdown(rows);
}

}  // namespace rlrun::cli
