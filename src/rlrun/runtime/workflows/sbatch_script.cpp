#include "rlrun/runtime/workflows/sbatch_script.hpp"

#include <cctype>
#include <filesystem>

#include "rlrun/core/errors.hpp"

namespace rlrun {

namespace fs = std::filesystem;

namespace {

// A path as one argument of a `#SBATCH` line, for sbatch's tokenizer (see the header): inside
// double quotes, with \ and " escaped by a backslash; % doubled because sbatch expands %A, %a,
// %j ... in --output names and writes %% as one % (sbatch(1), "filename pattern").
std::string sbatch_quoted_path(const std::string& path) {
  std::string out = "\"";
  for (char c : path) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '%') out += '%';
    out += c;
  }
  return out + "\"";
}

}  // namespace

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'')
      out += "'\\''";  // close the quote, an escaped quote, open again
    else
      out += c;
  }
  return out + "'";
}

std::string script_path_problem(const std::string& path) {
  for (char c : path)
    if (is_control_char(c))
      return "the path " + printable_value(path) +
             " contains a control character (a newline?), which no line of an sbatch script "
             "can hold safely; use a directory without it";
  return "";
}

std::string slurm_array_script(const SlurmArrayJob& job) {
  for (const std::string& path : {job.script, job.output_dir}) {
    const std::string problem = script_path_problem(path);
    if (!problem.empty()) throw UsageError("cannot write the sbatch script: " + problem);
  }
  if (!script_path_problem(job.command).empty())
    throw UsageError("cannot write the sbatch script: the command " + printable_value(job.command) +
                     " contains a control character (a newline?), which no line of an sbatch "
                     "script can hold safely");
  const SlurmOptions& s = job.options;
  // The options were checked where they were read (the sweep or study file, the manifest);
  // checked again here because this is where they become script text.
  const auto option = [](const std::string& key, const std::string& value) {
    const std::string problem = slurm_value_problem(key, value);
    if (!problem.empty()) throw UsageError("cannot write the sbatch script: " + problem);
  };
  option("time", s.time);
  option("mem", s.mem);
  option("partition", s.partition);
  option("cpus_per_task", std::to_string(s.cpus_per_task));
  for (const std::string& line : s.extra) option("extra", line);
  if (job.tasks < 1) throw UsageError("cannot write the sbatch script: no array task");

  // The job name reduced to [A-Za-z0-9._+-].
  std::string job_name;
  for (char c : job.name)
    job_name +=
        std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '+' || c == '-'
            ? c
            : '-';
  std::string text = "#!/bin/bash\n";
  for (const std::string& line : job.comment) {
    if (!script_path_problem(line).empty())
      throw UsageError("cannot write the sbatch script: a control character in its comment");
    text += "# " + line + "\n";
  }
  text += "# Submit with: sbatch " + shell_quote(job.script) + "\n";
  text += "#SBATCH --job-name=" + (job_name.empty() ? std::string("rlrun") : job_name) + "\n";
  text += "#SBATCH --array=0-" + std::to_string(job.tasks - 1) + "\n";
  text += "#SBATCH --output=" + sbatch_quoted_path(job.output_dir + "/") + "%A_%a.out\n";
  text += "#SBATCH --cpus-per-task=" + std::to_string(s.cpus_per_task) + "\n";
  if (!s.time.empty()) text += "#SBATCH --time=" + s.time + "\n";
  if (!s.mem.empty()) text += "#SBATCH --mem=" + s.mem + "\n";
  if (!s.partition.empty()) text += "#SBATCH --partition=" + s.partition + "\n";
  for (const std::string& line : s.extra) text += "#SBATCH " + line + "\n";
  text += "exec " + job.command + "\n";
  return text;
}

std::string slurm_script(const Sweep& sweep, const std::string& rlrun_binary,
                         const std::vector<std::string>& run_args) {
  const fs::path dir = fs::path(sweep.manifest).parent_path();
  SlurmArrayJob job;
  job.name = sweep.name.empty() ? "sweep" : sweep.name;
  job.script = (dir / "sweep.sbatch").string();
  job.output_dir = (dir / "slurm").string();
  job.tasks = static_cast<int>(sweep.runs.size());
  job.options = sweep.slurm;
  job.comment = {"Written by: rlrun sweep slurm " + shell_quote(sweep.manifest),
                 "Task i trains run i of the manifest (a finished run is skipped, an interrupted "
                 "one resumed)."};
  const int threads = sweep.slurm.cpus_per_task;  // the CPUs Slurm gives each task
  for (const std::string& arg : run_args)
    if (!script_path_problem(arg).empty())
      throw UsageError("cannot write the sbatch script: the argument " + printable_value(arg) +
                       " contains a control character (a newline?), which no line of an "
                       "sbatch script can hold safely");
  job.command = shell_quote(rlrun_binary) + " --threads " + std::to_string(threads) +
                " sweep run " + shell_quote(sweep.manifest) + " --index \"$SLURM_ARRAY_TASK_ID\"";
  for (const std::string& arg : run_args) {  // appended piece by piece: GCC 12's -Wrestrict
    job.command += ' ';
    job.command += shell_quote(arg);
  }
  return slurm_array_script(job);
}

}  // namespace rlrun
