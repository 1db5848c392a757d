// texproc build: runs the jobs of a recipe (docs/recipes.md). Each job is
// the command line `texproc COMMAND INPUTS -o OUTPUT --OPTION VALUE...`,
// parsed by the same parser as the command itself, so a recipe accepts
// exactly what the command line does and its mistakes are named with the
// recipe's line and key.
#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <functional>

#include "batch.h"
#include "build_state.h"
#include "tool_info.h"
#include "texproc/version.h"
#include "report.h"
#include "commands.h"
#include "common.h"
#include "recipe.h"
#include "texproc/error.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct BuildArgs {
  std::string recipe, out_dir;
  std::vector<std::string> only;
  bool emit_actions = false;
};

// Options that belong to the run, not to a job: given on the build command
// line, they apply to every job.
bool run_level_option(const std::string& key) {
  static const char* keys[] = {"threads",
                               "jobs",
                               "j",
                               "force",
                               "f",
                               "quiet",
                               "q",
                               "verbose",
                               "v",
                               "depfile",
                               "dry-run",
                               "n",
                               "json",
                               "progress",
                               "fail-fast",
                               "skip-existing",
                               "write-if-changed",
                               "output",
                               "o",
                               "recursive",
                               "r",
                               "file-list",
                               "help",
                               "h",
                               "shard",
                               "timings",
                               "ocio-config"};
  return std::any_of(std::begin(keys), std::end(keys), [&](const char* k) { return key == k; });
}

// Where in the recipe a message about a job points: the option it names
// ("--format"), else the job.
std::string locate(const Recipe& r, const RecipeJob& j, const std::string& message) {
  for (const RecipeOption& o : j.options) {
    const std::string flag = "--" + o.key;
    const auto at = message.find(flag);
    if (at != std::string::npos) {
      const std::size_t end = at + flag.size();
      const bool whole = end == message.size() || !(std::isalnum(static_cast<unsigned char>(message[end])) ||
                                                    message[end] == '-' || message[end] == '_');
      if (whole) return where(r, j, o.line) + ": options." + o.key;
    }
  }
  return where(r, j, 0);
}

// One run of a job's command: the job's own options for the files no
// override names, or one override's options for the files it names.
struct Unit {
  const RecipeJob* job = nullptr;
  int override_index = -1;  // -1: the job's own options
  std::vector<RecipeOption> options;
  std::string signature;  // what change tracking compares: command, output, recursion, options
};

std::vector<Unit> units_of(const RecipeJob& j) {
  std::vector<Unit> out;
  auto add = [&](int k, std::vector<RecipeOption> options) {
    Unit u;
    u.job = &j;
    u.override_index = k;
    u.options = std::move(options);
    std::string text = j.command + "\n" + j.output + "\n" + (j.recursive ? "r" : "") + "\n";
    for (const RecipeOption& o : u.options) {
      text += o.key + (o.flag ? "!" : "=");
      for (const std::string& v : o.values) text += v + '\x1f';
      text += '\n';
    }
    u.signature = hash_bytes(text);
    out.push_back(std::move(u));
  };
  add(-1, j.options);
  for (std::size_t k = 0; k < j.overrides.size(); ++k) add(int(k), merge_options(j.options, j.overrides[k].options));
  return out;
}

std::string job_name(const RecipeJob& j) { return j.name.empty() ? "jobs[" + std::to_string(j.index) + "]" : j.name; }

struct PreparedJob {
  const RecipeJob* job = nullptr;
  std::unique_ptr<CLI::App> app;
  CLI::App* command = nullptr;
};

const std::vector<std::string>& command_names() {
  static const std::vector<std::string> valid = {"mip", "compress", "normalmap",  "conemap",
                                                 "sat", "sat blur", "decompress", "cubemap"};
  return valid;
}

// The command words and options of a unit, as on the command line.
std::vector<std::string> option_args(const Recipe& r, const Unit& u, const CLI::App* command) {
  const RecipeJob& j = *u.job;
  std::vector<std::string> args;
  for (const RecipeOption& o : u.options) {
    const std::string at = where(r, j, o.line) + ": options." + o.key;
    if (run_level_option(o.key)) {
      throw Error(ErrorCode::bad_arguments, at + ": belongs to the whole run: give it to `texproc build` instead");
    }
    const CLI::Option* opt = command->get_option_no_throw("--" + o.key);
    if (!opt) {
      throw Error(ErrorCode::bad_arguments,
                  at + ": unknown option for " + j.command + " (see `texproc " + j.command + " --help`)");
    }
    const bool is_flag = opt->get_expected_max() == 0;
    if (is_flag && !o.flag) throw Error(ErrorCode::bad_arguments, at + ": is a switch: write " + o.key + " = true");
    if (!is_flag && o.flag) throw Error(ErrorCode::bad_arguments, at + ": needs a value, not true");
    args.push_back("--" + o.key);
    args.insert(args.end(), o.values.begin(), o.values.end());
  }
  return args;
}

std::vector<std::string> command_words(const RecipeJob& j) {
  return j.command == "sat blur" ? std::vector<std::string>{"sat", "blur"} : std::vector<std::string>{j.command};
}

PreparedJob prepare(const Recipe& r, const Unit& u, const std::vector<std::string>& inputs) {
  const RecipeJob& j = *u.job;
  PreparedJob p;
  p.job = &j;
  p.app = std::make_unique<CLI::App>();
  add_all_commands(*p.app);
  const auto& valid = command_names();
  if (std::find(valid.begin(), valid.end(), j.command) == valid.end()) {
    throw Error(ErrorCode::bad_arguments, where(r, j, j.command_line) + ": command: unknown command '" + j.command +
                                              "' (valid: " + join(valid) + ")");
  }
  p.command =
      j.command == "sat blur" ? p.app->get_subcommand("sat")->get_subcommand("blur") : p.app->get_subcommand(j.command);
  std::vector<std::string> args = command_words(j);
  args.insert(args.end(), inputs.begin(), inputs.end());
  args.insert(args.end(), {"-o", j.output});
  if (j.recursive) args.push_back("-r");
  const std::vector<std::string> opts = option_args(r, u, p.command);
  args.insert(args.end(), opts.begin(), opts.end());
  // The run-level options (--threads, --force...) are the build's own:
  // RunOptions, which the job's parser shares.
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last first
  try {
    p.app->parse(args);
  } catch (const CLI::ParseError& e) {
    throw Error(ErrorCode::bad_arguments, locate(r, j, e.what()) + ": " + e.what());
  }
  return p;
}

// The files of a job a unit takes: not excluded, and named by its override
// (or by none, for the job's own options). Null when the job has neither.
std::function<bool(const std::string&)> selector(const Unit& u) {
  const RecipeJob& j = *u.job;
  if (j.excludes.empty() && j.overrides.empty()) return nullptr;
  return [&j, k = u.override_index](const std::string& f) { return !excluded(j, f) && override_of(j, f) == k; };
}

// The command whose runner runs the job (`sat` for `sat blur`).
CLI::App* top_command(const PreparedJob& p) {
  return p.command->get_parent() == p.app.get() ? p.command : p.command->get_parent();
}

// The outputs a recipe has written, kept beside them in
// ".RECIPE_FILE_NAME.outputs" (one path a line, relative to the folder the
// outputs are taken from), so that an incremental build replaces only files
// it made, never a source that a job's output happens to name.
struct OwnedOutputs {
  fs::path root, file;
  std::set<std::string> keys;  // output_key of each
  std::vector<std::string> lines;

  OwnedOutputs(const fs::path& root_folder, const std::string& recipe) : root(root_folder) {
    file = root / ("." + fs::path(recipe).filename().string() + ".outputs");
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
      if (!line.empty()) add_relative(line);
    }
  }
  void add_relative(const std::string& rel) {
    if (keys.insert(output_key((root / rel).string())).second) lines.push_back(rel);
  }
  void add(const std::string& output) {
    std::error_code ec;
    const fs::path rel = fs::relative(fs::absolute(output, ec), fs::absolute(root, ec), ec);
    add_relative(ec || rel.empty() ? fs::absolute(output).lexically_normal().string() : rel.string());
  }
  // Writes the list, merged with what another build sharing the folder
  // recorded since this one read it (under the folder's lock).
  void save() {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
      if (!line.empty()) add_relative(line);
    }
    std::string text;
    for (const std::string& l : lines) text += l + "\n";
    write_file_atomic(file.string(), text, CommitPolicy::replace);
  }
};

// Every job's files, planned before any job runs.
struct JobPlan {
  std::vector<std::string> inputs;  // the job's inputs as arguments, globs expanded
  std::vector<const InputSpec*> unmatched;
  std::vector<std::vector<BatchSession::PlannedFile>> units;  // per unit
  std::set<std::string> outputs;                              // absolute
};

struct Plan {
  std::vector<std::vector<Unit>> units;  // per job
  std::vector<JobPlan> jobs;
  std::vector<std::string> planned;  // every output, absolute, sorted
  std::vector<std::size_t> order;    // the jobs, producers before consumers
};

// Checks the units' options, inputs and output names and plans their files
// (BatchSession::check_only), with globs expanded against the files on
// disk and `planned`.
std::vector<JobPlan> plan_pass(const Recipe& r, const std::vector<std::vector<Unit>>& units,
                               const std::vector<std::string>& planned) {
  BatchSession& s = batch_session();
  std::vector<JobPlan> out(units.size());
  for (std::size_t j = 0; j < units.size(); ++j) {
    const RecipeJob& job = *units[j].front().job;
    JobPlan& jp = out[j];
    jp.inputs = expand_job_inputs(job, planned, &jp.unmatched);
    jp.units.resize(units[j].size());
    if (jp.inputs.empty()) continue;
    for (std::size_t k = 0; k < units[j].size(); ++k) {
      PreparedJob p = prepare(r, units[j][k], jp.inputs);
      s.check_only = true;
      s.plans = &jp.units[k];
      s.select = selector(units[j][k]);
      try {
        (*runner_of(*top_command(p)))();
      } catch (const Error& e) {
        s.check_only = false;
        s.plans = nullptr;
        s.select = nullptr;
        throw Error(e.code(), locate(r, job, e.what()) + ": " + e.what());
      }
      s.check_only = false;
      s.plans = nullptr;
      s.select = nullptr;
      for (const auto& f : jp.units[k]) {
        for (const std::string& o : f.outputs) jp.outputs.insert(absolute_path(o));
      }
    }
  }
  return out;
}

// Whether job `consumer` reads what job `producer` writes: one of its files'
// inputs is a planned output, or an output lies under a folder it reads.
bool reads_from(const RecipeJob& consumer, const JobPlan& c, const JobPlan& producer) {
  for (const auto& unit : c.units) {
    for (const auto& f : unit) {
      for (const std::string& in : f.inputs) {
        if (producer.outputs.count(absolute_path(in))) return true;
      }
    }
  }
  for (const InputSpec& in : consumer.inputs) {
    if (in.glob) continue;
    std::string folder = absolute_path(in.path);
    if (folder.empty() || folder.back() != '/') folder += '/';
    for (const std::string& o : producer.outputs) {
      if (o.compare(0, folder.size(), folder) == 0) return true;
    }
  }
  return false;
}

// Plans the recipe: globs are expanded against the disk and the other jobs'
// outputs until nothing new appears, the jobs are ordered producers first
// (recipe order among independent jobs), and cycles and patterns that match
// nothing are refused.
Plan plan_recipe(const Recipe& r) {
  Plan plan;
  for (const RecipeJob& j : r.jobs) plan.units.push_back(units_of(j));
  const std::size_t n = r.jobs.size();
  for (std::size_t pass = 0; pass <= n + 1; ++pass) {
    plan.jobs = plan_pass(r, plan.units, plan.planned);
    std::set<std::string> all;
    for (const JobPlan& jp : plan.jobs) all.insert(jp.outputs.begin(), jp.outputs.end());
    std::vector<std::string> next(all.begin(), all.end());
    if (next == plan.planned) break;
    plan.planned = std::move(next);
  }
  // reads[a]: the jobs a reads from.
  std::vector<std::vector<std::size_t>> reads(n);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      if (!reads_from(r.jobs[a], plan.jobs[a], plan.jobs[b])) continue;
      if (a == b) {
        throw Error(
            ErrorCode::bad_arguments,
            where(r, r.jobs[a], r.jobs[a].output_line) +
                ": reads its own outputs (its inputs match what it writes): write them elsewhere or exclude them");
      }
      reads[a].push_back(b);
    }
  }
  // Producers first; among jobs that are ready, the one first in the recipe.
  std::vector<std::size_t> waiting(n);
  std::vector<std::vector<std::size_t>> readers(n);
  for (std::size_t a = 0; a < n; ++a) {
    waiting[a] = reads[a].size();
    for (std::size_t b : reads[a]) readers[b].push_back(a);
  }
  std::set<std::size_t> ready;
  for (std::size_t a = 0; a < n; ++a)
    if (waiting[a] == 0) ready.insert(a);
  while (!ready.empty()) {
    const std::size_t a = *ready.begin();
    ready.erase(ready.begin());
    plan.order.push_back(a);
    for (std::size_t c : readers[a])
      if (--waiting[c] == 0) ready.insert(c);
  }
  if (plan.order.size() < n) {
    // Walk back along "reads from" among the jobs left until one repeats.
    std::size_t a = 0;
    while (waiting[a] == 0) ++a;
    std::vector<std::size_t> path;
    while (std::find(path.begin(), path.end(), a) == path.end()) {
      path.push_back(a);
      a = *std::find_if(reads[a].begin(), reads[a].end(), [&](std::size_t b) { return waiting[b] > 0; });
    }
    path.erase(path.begin(), std::find(path.begin(), path.end(), a));
    std::string chain = "job '" + job_name(r.jobs[path[0]]) + "'";
    for (std::size_t k = 1; k <= path.size(); ++k) {
      chain += " reads outputs of job '" + job_name(r.jobs[path[k % path.size()]]) + "'";
      if (k < path.size()) chain += ", which";
    }
    throw Error(ErrorCode::bad_arguments, where(r, r.jobs[path[0]], 0) + ": jobs form a cycle: " + chain);
  }
  for (std::size_t j = 0; j < n; ++j) {
    for (const InputSpec* in : plan.jobs[j].unmatched) {
      throw Error(ErrorCode::bad_arguments, where(r, r.jobs[j], in->line) + ": inputs: '" + in->text +
                                                "' matches no file (on disk or written by another job)");
    }
  }
  return plan;
}

// Before any job runs: no output of one job may be a file that another job
// reads, unless this recipe made it (an intermediate).
void check_outputs_against_inputs(const Recipe& r, const Plan& plan, const OwnedOutputs& owned) {
  std::map<std::pair<dev_t, ino_t>, std::size_t> reader;  // an input file -> the job that reads it
  for (std::size_t j = 0; j < plan.jobs.size(); ++j) {
    for (const auto& unit : plan.jobs[j].units) {
      for (const auto& f : unit) {
        for (const std::string& in : f.inputs) {
          struct stat st {};
          if (::stat(in.c_str(), &st) == 0) reader.emplace(std::pair{st.st_dev, st.st_ino}, j);
        }
      }
    }
  }
  for (std::size_t j = 0; j < plan.jobs.size(); ++j) {
    for (const std::string& out : plan.jobs[j].outputs) {
      struct stat st {};
      if (::stat(out.c_str(), &st) != 0 || owned.keys.count(output_key(out))) continue;
      const auto it = reader.find({st.st_dev, st.st_ino});
      if (it == reader.end()) continue;
      throw Error(ErrorCode::bad_arguments,
                  where(r, r.jobs[j], r.jobs[j].output_line) + ": output " + out + " is an input of " +
                      where(r, r.jobs[it->second], 0) +
                      " and was not made by this recipe; outputs never overwrite sources: choose another name");
    }
  }
}

// A path as an action names it: relative to the recipe's folder when under
// it, else absolute.
std::string action_path(const fs::path& base, const std::string& p) {
  const fs::path abs = fs::path(absolute_path(p));
  const fs::path rel = abs.lexically_relative(base);
  if (rel.empty() || *rel.begin() == "..") return abs.string();
  return rel.string();
}

// --emit-actions: one action a file, in the order the build runs them.
Json::Value emit_actions(const Recipe& r, const Plan& plan, const std::vector<std::string>& only) {
  const fs::path base = fs::path(
      absolute_path(fs::path(r.path).parent_path().string().empty() ? "." : fs::path(r.path).parent_path().string()));
  const std::string ocio = run_options().ocio_config;
  Json::Value actions(Json::arrayValue);
  for (std::size_t j : plan.order) {
    const RecipeJob& job = r.jobs[j];
    if (!only.empty() && std::find(only.begin(), only.end(), job.name) == only.end()) continue;
    for (std::size_t k = 0; k < plan.units[j].size(); ++k) {
      const Unit& u = plan.units[j][k];
      for (const auto& f : plan.jobs[j].units[k]) {
        Json::Value argv(Json::arrayValue);
        argv.append("texproc");
        for (const std::string& w : command_words(job)) argv.append(w);
        argv.append(action_path(base, f.input));
        argv.append("-o");
        argv.append(action_path(base, f.output));
        for (const RecipeOption& o : u.options) {
          argv.append("--" + o.key);
          const bool path = o.key == "radius-map" || o.key == "preview";
          for (const std::string& v : o.values) argv.append(path ? action_path(base, v) : v);
        }
        if (!ocio.empty()) {
          argv.append("--ocio-config");
          argv.append(action_path(base, ocio));
        }
        Json::Value a(Json::objectValue), ins(Json::arrayValue), outs(Json::arrayValue);
        for (const std::string& in : f.inputs) ins.append(action_path(base, in));
        for (const std::string& o : f.outputs) outs.append(action_path(base, o));
        a["job"] = job_name(job);
        a["argv"] = argv;
        a["inputs"] = ins;
        a["outputs"] = outs;
        a["outputs_known"] = f.outputs_known;
        actions.append(a);
      }
    }
  }
  Json::Value root(Json::objectValue), tool(Json::objectValue);
  tool["version"] = version_string();
  tool["digest"] = tool_digest();
  root["tool"] = tool;
  root["recipe"] = fs::path(r.path).filename().string();
  root["actions"] = actions;
  return root;
}

int run_build(const BuildArgs& a) {
  const Recipe recipe = read_recipe(a.recipe, a.out_dir);
  record_input(a.recipe);
  for (const auto& name : a.only) {
    if (std::none_of(recipe.jobs.begin(), recipe.jobs.end(), [&](const RecipeJob& j) { return j.name == name; })) {
      throw Error(ErrorCode::bad_arguments, a.recipe + ": --job " + name + ": no job has that name");
    }
  }
  // Every job is parsed and planned before any runs: a mistake anywhere
  // stops the build before it writes anything.
  const Plan plan = plan_recipe(recipe);
  if (a.emit_actions) {
    std::cout << to_json(emit_actions(recipe, plan, a.only));
    return 0;
  }
  fs::path root = a.out_dir.empty() ? fs::path(a.recipe).parent_path() : fs::path(a.out_dir);
  if (root.empty()) root = ".";
  OwnedOutputs owned(root, a.recipe);
  check_outputs_against_inputs(recipe, plan, owned);
  BuildState state(root, fs::path(a.recipe).filename().string());
  // Incremental unless --force: a file is rebuilt when its job's settings,
  // its inputs' bytes or texproc changed; only outputs this recipe made may
  // be replaced.
  BatchSession& s = batch_session();
  s.incremental = !run_options().force;
  s.owned_outputs = owned.keys;
  const Unit* current = nullptr;
  s.why_rebuild = [&](const FileReport& r) { return state.why_rebuild(r, current->signature); };
  int rc = 0;
  for (std::size_t j : plan.order) {
    const RecipeJob& job = recipe.jobs[j];
    if (!a.only.empty() && std::find(a.only.begin(), a.only.end(), job.name) == a.only.end()) continue;
    const std::vector<std::string> inputs = expand_job_inputs(job, plan.planned);
    const std::size_t first = session_reports().size();
    int job_rc = 0;
    for (const Unit& u : plan.units[j]) {
      current = &u;
      const std::size_t unit_first = session_reports().size();
      try {
        PreparedJob p = prepare(recipe, u, inputs);
        s.select = selector(u);
        const int unit_rc = (*runner_of(*top_command(p)))();
        if (unit_rc != 0 && job_rc == 0) job_rc = unit_rc;
      } catch (const Error& e) {
        print_error("build", locate(recipe, job, e.what()) + ": " + in_cli_terms(e.what()));
        if (job_rc == 0) job_rc = int(e.code());
      }
      s.select = nullptr;
      if (run_options().dry_run) continue;
      for (std::size_t i = unit_first; i < session_reports().size(); ++i) {
        const FileReport& fr = session_reports()[i];
        if (fr.status == FileStatus::ok) state.record(fr, u.signature);
      }
      if (job_rc != 0 && run_options().fail_fast) break;
    }
    bool wrote = false;
    for (std::size_t i = first; i < session_reports().size(); ++i) {
      FileReport& fr = session_reports()[i];
      fr.details["job"] = job_name(job);
      if (fr.status != FileStatus::ok) continue;
      if (run_options().dry_run) {
        for (const std::string& o : fr.outputs) s.pending[absolute_path(o)] = "'" + job_name(job) + "'";
        continue;
      }
      for (const std::string& o : fr.outputs) owned.add(o);
      wrote = true;
    }
    if (!run_options().dry_run && (wrote || state.dirty())) {
      std::error_code ec;
      fs::create_directories(root, ec);
      FileLock lock((root / ("." + fs::path(a.recipe).filename().string() + ".lock")).string());
      if (wrote) owned.save();
      state.save();
      s.owned_outputs = owned.keys;
    }
    if (job_rc != 0 && rc == 0) rc = job_rc;
    if (job_rc != 0 && run_options().fail_fast) break;
  }
  s.why_rebuild = nullptr;
  return rc;
}

}  // namespace

void add_build_command(CLI::App& app) {
  auto args = std::make_shared<BuildArgs>();
  CLI::App* cmd = app.add_subcommand("build", "Run the jobs of a recipe (TOML or JSON): a project's texture settings.");
  cmd->footer(
      "A recipe lists jobs: command, inputs (files, folders, glob patterns), output (file, folder/ or\n"
      "template) and options, as on the command line. Paths are relative to the recipe's folder.\n"
      "Run-level options (--threads, --jobs, --force, --depfile, --dry-run, --json...) are given here and\n"
      "apply to every job. See docs/recipes.md and samples/recipe.toml.");
  cmd->add_option("recipe", args->recipe, "Recipe file (.toml or .json)")->required();
  cmd->add_option("--out-dir", args->out_dir,
                  "Take relative outputs from this folder instead of the recipe's (out-of-source builds)");
  cmd->add_option("--job", args->only, "Run only the jobs with these names (repeatable)");
  cmd->add_flag("--emit-actions", args->emit_actions,
                "Print the recipe's actions as JSON and run nothing: per file, the argv, inputs and outputs (paths "
                "relative to the recipe's folder) and the tool digest, for build systems (docs/scale-out.md)");
  add_common_options(*cmd);
  set_runner(*cmd, [args] { return run_build(*args); });
}

}  // namespace texproc::cli
