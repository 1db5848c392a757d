// The end of a run: the --json summary of every file and the closing
// line that lists the failures.
#include <filesystem>
#include <iostream>

#include "batch.h"
#include "report.h"

namespace fs = std::filesystem;

namespace texproc::cli {

const char* to_string(FileStatus s) {
  switch (s) {
    case FileStatus::ok:
      return "ok";
    case FileStatus::failed:
      return "failed";
    case FileStatus::skipped:
      return "skipped";
    case FileStatus::not_run:
      return "not_run";
  }
  return "ok";
}

void print_json_summary(const std::string& command, int exit_code, const std::string& error) {
  Json::Value root(Json::objectValue);
  root["command"] = command;
  root["exit_code"] = exit_code;
  if (!error.empty()) root["error"] = error;
  Json::Value files(Json::arrayValue);
  int count[4] = {};  // by FileStatus
  for (const auto& r : session_reports()) {
    Json::Value f(Json::objectValue);
    f["input"] = r.input;
    Json::Value ins(Json::arrayValue);
    for (const auto& in : r.inputs) ins.append(in);
    f["inputs"] = ins;
    Json::Value outs(Json::arrayValue);
    for (const auto& o : r.outputs) outs.append(o);
    f["outputs"] = outs;
    f["status"] = to_string(r.status);
    if (r.status == FileStatus::failed) {
      f["error"] = r.error;
      f["exit_code"] = int(r.code);
    }
    if (r.status == FileStatus::ok) {
      std::error_code ec;
      const auto in_bytes = fs::file_size(r.input, ec);
      if (!ec) f["input_bytes"] = Json::UInt64(in_bytes);
      Json::UInt64 out_bytes = 0;
      for (const auto& o : r.outputs) {
        const auto n = fs::file_size(o, ec);
        if (!ec) out_bytes += n;
      }
      if (!run_options().dry_run) {
        f["output_bytes"] = out_bytes;
        if (run_options().timings) f["seconds"] = r.seconds;
      }
      for (const auto& key : r.details.getMemberNames()) {
        // Times differ from run to run: only with --timings, so that a
        // summary can be a build's (cached) output.
        const bool timing = key == "phases" || (key.size() > 8 && key.compare(key.size() - 8, 8, "_seconds") == 0);
        if (!timing || run_options().timings) f[key] = r.details[key];
      }
    }
    ++count[int(r.status)];
    files.append(f);
  }
  root["files"] = files;
  for (FileStatus st : {FileStatus::ok, FileStatus::failed, FileStatus::skipped, FileStatus::not_run}) {
    root[to_string(st)] = count[int(st)];
  }
  root["dry_run"] = run_options().dry_run;
  std::cout << to_json(root) << "\n";
}

void print_failure_summary(const std::string& command) {
  const auto& reports = session_reports();
  std::vector<const FileReport*> failed;
  std::size_t not_run = 0;
  for (const auto& r : reports) {
    if (r.status == FileStatus::failed) failed.push_back(&r);
    if (r.status == FileStatus::not_run) ++not_run;
  }
  if (reports.size() < 2 || failed.empty()) return;
  std::string head = "texproc " + command + ": " + std::to_string(failed.size()) + " of " +
                     std::to_string(reports.size()) + " files failed";
  if (not_run) head += ", " + std::to_string(not_run) + " not run (--fail-fast)";
  print_note(head + ":");
  for (const FileReport* r : failed) print_note("  " + about(r->input, r->error));
}

}  // namespace texproc::cli
