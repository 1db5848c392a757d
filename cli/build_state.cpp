#include "build_state.h"

#include <json/reader.h>
#include <json/value.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fstream>
#include <sstream>

#include "texproc/error.h"
#include "texproc/tools.h"
#include "tool_info.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

bool stat_of(const std::string& path, std::uintmax_t& size, std::int64_t& mtime_ns) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return false;
  size = std::uintmax_t(st.st_size);
  mtime_ns = std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec;
  return true;
}

// A file's inputs without repeats, in order.
std::vector<std::string> unique_inputs(const FileReport& r) {
  std::vector<std::string> out;
  for (const std::string& in : r.inputs) {
    if (std::find(out.begin(), out.end(), in) == out.end()) out.push_back(in);
  }
  return out;
}

}  // namespace

FileLock::FileLock(const std::string& path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error(ErrorCode::io, path + ": cannot open lock file: " + std::strerror(errno));
  while (::flock(fd_, LOCK_EX) != 0) {
    if (errno == EINTR) continue;
    const int e = errno;
    ::close(fd_);
    throw Error(ErrorCode::io, path + ": cannot lock: " + std::strerror(e));
  }
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

BuildState::BuildState(const fs::path& root, const std::string& recipe_file_name)
    : root_(fs::absolute(root).lexically_normal()), file_(root / ("." + recipe_file_name + ".state")) {
  entries_ = load(file_);
}

std::map<std::string, BuildState::Entry> BuildState::load(const fs::path& file) {
  std::map<std::string, Entry> out;
  std::ifstream in(file, std::ios::binary);
  if (!in) return out;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  Json::CharReaderBuilder b;
  std::unique_ptr<Json::CharReader> reader(b.newCharReader());
  Json::Value root;
  std::string errors;
  if (!reader->parse(text.data(), text.data() + text.size(), &root, &errors) || !root.isObject() ||
      root["version"] != 1 || !root["files"].isObject()) {
    return out;
  }
  auto stamps = [](const Json::Value& list, bool with_hash) {
    std::vector<Stamp> v;
    for (const Json::Value& s : list) {
      Stamp st;
      st.path = s["path"].asString();
      st.size = s["size"].asUInt64();
      st.mtime_ns = s["mtime_ns"].asInt64();
      if (with_hash) st.hash = s["hash"].asString();
      v.push_back(std::move(st));
    }
    return v;
  };
  try {
    for (const std::string& key : root["files"].getMemberNames()) {
      const Json::Value& f = root["files"][key];
      Entry e;
      e.signature = f["signature"].asString();
      e.tool = f["tool"].asString();
      e.inputs = stamps(f["inputs"], true);
      e.outputs = stamps(f["outputs"], false);
      out[key] = std::move(e);
    }
  } catch (const Json::Exception&) {
    out.clear();  // not ours, or damaged: rebuild everything
  }
  return out;
}

std::string BuildState::relative(const std::string& path) const {
  std::error_code ec;
  const fs::path abs = fs::absolute(path, ec).lexically_normal();
  const fs::path rel = abs.lexically_relative(root_);
  return rel.empty() ? abs.string() : rel.string();
}

std::string BuildState::absolute(const std::string& rel) const {
  const fs::path p(rel);
  return p.is_absolute() ? rel : (root_ / p).lexically_normal().string();
}

std::string BuildState::why_rebuild(const FileReport& r, const std::string& signature) {
  if (r.outputs.empty()) return "new";
  const std::string key = relative(r.outputs.front());
  const auto it = entries_.find(key);
  if (it == entries_.end()) return "new";
  Entry& e = it->second;
  if (e.signature != signature) return "job settings changed";
  if (e.tool != tool_digest()) return "texproc changed";
  if (e.outputs.size() != r.outputs.size()) return "outputs changed";
  for (std::size_t i = 0; i < r.outputs.size(); ++i) {
    const Stamp& s = e.outputs[i];
    if (s.path != relative(r.outputs[i])) return "outputs changed";
    std::uintmax_t size = 0;
    std::int64_t mtime = 0;
    if (!stat_of(r.outputs[i], size, mtime)) return "output missing: " + r.outputs[i];
    if (size != s.size || mtime != s.mtime_ns) return "output changed: " + r.outputs[i];
  }
  const std::vector<std::string> inputs = unique_inputs(r);
  if (inputs.size() != e.inputs.size()) return "inputs changed";
  bool refreshed = false;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    Stamp& s = e.inputs[i];
    if (s.path != relative(inputs[i])) return "inputs changed";
    std::uintmax_t size = 0;
    std::int64_t mtime = 0;
    if (!stat_of(inputs[i], size, mtime)) return "input missing: " + inputs[i];
    if (size == s.size && mtime == s.mtime_ns) continue;
    // Touched, checked out again, copied: the bytes decide.
    if (size != s.size || hash_file(inputs[i]) != s.hash) return "input changed: " + inputs[i];
    s.mtime_ns = mtime;
    refreshed = true;
  }
  if (refreshed) changed_.insert(key);
  return "";
}

void BuildState::record(const FileReport& r, const std::string& signature) {
  if (r.outputs.empty()) return;
  Entry e;
  e.signature = signature;
  e.tool = tool_digest();
  for (const std::string& in : unique_inputs(r)) {
    Stamp s;
    s.path = relative(in);
    if (!stat_of(in, s.size, s.mtime_ns)) return;  // gone: leave no record, the next run rebuilds
    s.hash = hash_file(in);
    e.inputs.push_back(std::move(s));
  }
  for (const std::string& out : r.outputs) {
    Stamp s;
    s.path = relative(out);
    if (!stat_of(out, s.size, s.mtime_ns)) return;
    e.outputs.push_back(std::move(s));
  }
  const std::string key = relative(r.outputs.front());
  entries_[key] = std::move(e);
  changed_.insert(key);
}

void BuildState::save() {
  if (changed_.empty()) return;
  std::map<std::string, Entry> merged = load(file_);
  for (const std::string& key : changed_) merged[key] = entries_[key];
  Json::Value files(Json::objectValue);
  for (const auto& [key, e] : merged) {
    Json::Value f(Json::objectValue);
    f["signature"] = e.signature;
    f["tool"] = e.tool;
    Json::Value ins(Json::arrayValue), outs(Json::arrayValue);
    for (const Stamp& s : e.inputs) {
      Json::Value v(Json::objectValue);
      v["path"] = s.path;
      v["size"] = Json::UInt64(s.size);
      v["mtime_ns"] = Json::Int64(s.mtime_ns);
      v["hash"] = s.hash;
      ins.append(v);
    }
    for (const Stamp& s : e.outputs) {
      Json::Value v(Json::objectValue);
      v["path"] = s.path;
      v["size"] = Json::UInt64(s.size);
      v["mtime_ns"] = Json::Int64(s.mtime_ns);
      outs.append(v);
    }
    f["inputs"] = ins;
    f["outputs"] = outs;
    files[key] = f;
  }
  Json::Value root(Json::objectValue);
  root["version"] = 1;
  root["files"] = files;
  std::error_code ec;
  fs::create_directories(file_.parent_path().empty() ? fs::path(".") : file_.parent_path(), ec);
  write_file_atomic(file_.string(), to_json(root), CommitPolicy::replace);
  entries_ = std::move(merged);
  changed_.clear();
}

}  // namespace texproc::cli
