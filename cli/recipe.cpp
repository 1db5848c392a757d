#include "recipe.h"

#include <glob.h>
#include <json/reader.h>
#include <json/value.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "texproc/error.h"

namespace fs = std::filesystem;

namespace texproc::cli {

namespace {

// The recipe as a plain tree with line numbers, from TOML or JSON.
struct Node {
  enum Kind { string, integer, real, boolean, array, table, other } kind = other;
  int line = 0;
  std::string text;  // string; numbers and booleans as written for the command line
  bool truth = false;
  std::vector<Node> items;
  std::vector<std::pair<std::string, Node>> fields;
  const Node* find(const std::string& key) const {
    for (const auto& [k, v] : fields)
      if (k == key) return &v;
    return nullptr;
  }
};

const char* kind_name(Node::Kind k) {
  switch (k) {
    case Node::string: return "a string";
    case Node::integer: return "an integer";
    case Node::real: return "a number";
    case Node::boolean: return "a boolean";
    case Node::array: return "an array";
    case Node::table: return "a table";
    case Node::other: return "a date or time";
  }
  return "?";
}

std::string number_text(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

Node from_toml(const toml::node& n) {
  Node out;
  out.line = int(n.source().begin.line);
  if (auto s = n.as_string()) {
    out.kind = Node::string;
    out.text = s->get();
  } else if (auto i = n.as_integer()) {
    out.kind = Node::integer;
    out.text = std::to_string(i->get());
  } else if (auto f = n.as_floating_point()) {
    out.kind = Node::real;
    out.text = number_text(f->get());
  } else if (auto flag = n.as_boolean()) {
    out.kind = Node::boolean;
    out.truth = flag->get();
    out.text = out.truth ? "true" : "false";
  } else if (auto list = n.as_array()) {
    out.kind = Node::array;
    for (const auto& item : *list) out.items.push_back(from_toml(item));
  } else if (auto t = n.as_table()) {
    out.kind = Node::table;
    for (const auto& [k, v] : *t) out.fields.emplace_back(std::string(k.str()), from_toml(v));
    // toml++ keeps keys sorted; present them in file order.
    std::stable_sort(out.fields.begin(), out.fields.end(),
                     [](const auto& a, const auto& b) { return a.second.line < b.second.line; });
  }
  return out;
}

Node from_json(const Json::Value& v, const std::vector<std::size_t>& line_starts) {
  Node out;
  const auto offset = std::size_t(std::max<std::ptrdiff_t>(0, v.getOffsetStart()));
  out.line = int(std::upper_bound(line_starts.begin(), line_starts.end(), offset) - line_starts.begin());
  switch (v.type()) {
    case Json::stringValue:
      out.kind = Node::string;
      out.text = v.asString();
      break;
    case Json::intValue:
    case Json::uintValue:
      out.kind = Node::integer;
      out.text = v.isInt64() ? std::to_string(v.asInt64()) : std::to_string(v.asUInt64());
      break;
    case Json::realValue:
      out.kind = Node::real;
      out.text = number_text(v.asDouble());
      break;
    case Json::booleanValue:
      out.kind = Node::boolean;
      out.truth = v.asBool();
      out.text = out.truth ? "true" : "false";
      break;
    case Json::arrayValue:
      out.kind = Node::array;
      for (const auto& item : v) out.items.push_back(from_json(item, line_starts));
      break;
    case Json::objectValue:
      out.kind = Node::table;
      for (const auto& k : v.getMemberNames()) out.fields.emplace_back(k, from_json(v[k], line_starts));
      std::stable_sort(out.fields.begin(), out.fields.end(),
                       [](const auto& a, const auto& b) { return a.second.line < b.second.line; });
      break;
    case Json::nullValue:
      out.kind = Node::other;
      break;
  }
  return out;
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& what) {
  throw Error(ErrorCode::bad_arguments, path + ":" + std::to_string(line) + ": " + what);
}

Node parse_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::io, path + ": cannot open recipe");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  std::string ext = fs::path(path).extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".json") {
    Json::CharReaderBuilder b;
    b["rejectDupKeys"] = true;
    b["allowComments"] = true;
    b["failIfExtra"] = true;
    std::unique_ptr<Json::CharReader> reader(b.newCharReader());
    Json::Value root;
    std::string errors;
    if (!reader->parse(text.data(), text.data() + text.size(), &root, &errors)) {
      // jsoncpp says "* Line 3, Column 5\n  Syntax error: ...": make it FILE:LINE: message.
      std::string msg = errors;
      int line = 0;
      const auto at = msg.find("Line ");
      if (at != std::string::npos) line = std::atoi(msg.c_str() + at + 5);
      const auto nl = msg.find('\n');
      if (nl != std::string::npos) msg = msg.substr(nl + 1);
      while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
      while (!msg.empty() && msg.front() == ' ') msg.erase(0, 1);
      fail(path, line, "invalid JSON: " + msg);
    }
    std::vector<std::size_t> line_starts{0};
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') line_starts.push_back(i + 1);
    return from_json(root, line_starts);
  }
  if (ext != ".toml") {
    throw Error(ErrorCode::bad_arguments, path + ": a recipe is a .toml or .json file");
  }
  try {
    const toml::table t = toml::parse(text, path);
    Node n = from_toml(t);
    n.line = 1;
    return n;
  } catch (const toml::parse_error& e) {
    fail(path, int(e.source().begin.line), "invalid TOML: " + std::string(e.description()));
  }
}

bool has_glob(const std::string& s) { return s.find_first_of("*?[") != std::string::npos; }

std::string resolve(const fs::path& base, const std::string& p) {
  if (p.empty() || fs::path(p).is_absolute() || base.empty()) return p;
  const bool folder = p.back() == '/';
  std::string r = (base / p).lexically_normal().string();
  if (folder && !r.empty() && r.back() != '/') r += '/';
  return r;
}

}  // namespace

std::string where(const Recipe& r, const RecipeJob& j, int line) {
  return r.path + ":" + std::to_string(line ? line : j.line) + ": " +
         (j.name.empty() ? "jobs[" + std::to_string(j.index) + "]" : "job '" + j.name + "'");
}

Recipe read_recipe(const std::string& path, const std::string& out_dir) {
  const Node root = parse_file(path);
  Recipe r;
  r.path = path;
  const fs::path base = fs::path(path).parent_path();
  for (const auto& [key, v] : root.fields) {
    if (key == "version") {
      if (v.kind != Node::integer || v.text != "1") fail(path, v.line, "version: this texproc reads version 1");
    } else if (key != "jobs") {
      fail(path, v.line, key + ": unknown key (valid at the top: version, jobs)");
    }
  }
  const Node* jobs = root.find("jobs");
  if (!jobs) fail(path, 1, "jobs: missing (a list of jobs: [[jobs]] in TOML, \"jobs\": [...] in JSON)");
  if (jobs->kind != Node::array || jobs->items.empty()) fail(path, jobs->line, "jobs: expected a non-empty array of tables");
  for (std::size_t i = 0; i < jobs->items.size(); ++i) {
    const Node& jn = jobs->items[i];
    RecipeJob j;
    j.index = int(i);
    j.line = jn.line;
    const std::string at = "jobs[" + std::to_string(i) + "]";
    if (jn.kind != Node::table) fail(path, jn.line, at + ": expected a table");
    auto string_field = [&](const char* key, bool required, std::string& out, int* line) {
      const Node* n = jn.find(key);
      if (!n) {
        if (required) fail(path, jn.line, at + "." + key + ": missing");
        return;
      }
      if (n->kind != Node::string || n->text.empty()) {
        fail(path, n->line, at + "." + key + ": expected a non-empty string, found " + kind_name(n->kind));
      }
      out = n->text;
      if (line) *line = n->line;
    };
    for (const auto& [key, v] : jn.fields) {
      static const char* known[] = {"name", "command", "inputs", "output", "recursive", "options"};
      if (std::find_if(std::begin(known), std::end(known), [&](const char* k) { return key == k; }) ==
          std::end(known)) {
        fail(path, v.line, at + "." + key + ": unknown key (valid: name, command, inputs, output, recursive, options)");
      }
    }
    string_field("name", false, j.name, nullptr);
    string_field("command", true, j.command, &j.command_line);
    string_field("output", true, j.output, &j.output_line);
    j.output = resolve(out_dir.empty() ? base : fs::path(out_dir), j.output);
    if (const Node* rec = jn.find("recursive")) {
      if (rec->kind != Node::boolean) fail(path, rec->line, at + ".recursive: expected true or false");
      j.recursive = rec->truth;
    }
    const Node* inputs = jn.find("inputs");
    if (!inputs) fail(path, jn.line, at + ".inputs: missing");
    std::vector<const Node*> in_nodes;
    if (inputs->kind == Node::string) {
      in_nodes.push_back(inputs);
    } else if (inputs->kind == Node::array && !inputs->items.empty()) {
      for (const Node& n : inputs->items) in_nodes.push_back(&n);
    } else {
      fail(path, inputs->line, at + ".inputs: expected a string or a non-empty array of strings");
    }
    for (std::size_t k = 0; k < in_nodes.size(); ++k) {
      const Node& n = *in_nodes[k];
      const std::string ik = at + ".inputs[" + std::to_string(k) + "]";
      if (n.kind != Node::string || n.text.empty()) fail(path, n.line, ik + ": expected a non-empty string");
      const std::string p = resolve(base, n.text);
      if (!has_glob(n.text)) {
        j.inputs.push_back(p);
        j.input_lines.push_back(n.line);
        continue;
      }
      glob_t g{};
      const int rc = ::glob(p.c_str(), GLOB_ERR, nullptr, &g);
      std::vector<std::string> found;
      for (std::size_t m = 0; rc == 0 && m < g.gl_pathc; ++m) found.push_back(g.gl_pathv[m]);
      ::globfree(&g);
      if (found.empty()) fail(path, n.line, ik + ": '" + n.text + "' matches no file");
      std::sort(found.begin(), found.end());
      for (auto& f : found) {
        j.inputs.push_back(f);
        j.input_lines.push_back(n.line);
      }
    }
    if (const Node* opts = jn.find("options")) {
      if (opts->kind != Node::table) fail(path, opts->line, at + ".options: expected a table of option = value");
      for (const auto& [key, v] : opts->fields) {
        RecipeOption o;
        o.key = key;
        o.line = v.line;
        const std::string ok = at + ".options." + key;
        switch (v.kind) {
          case Node::boolean:
            if (!v.truth) continue;  // a false flag is the default
            o.flag = true;
            break;
          case Node::string:
            // Options that name files are paths like inputs and output.
            if (key == "radius-map") {
              o.values.push_back(resolve(base, v.text));
            } else if (key == "preview") {
              o.values.push_back(resolve(out_dir.empty() ? base : fs::path(out_dir), v.text));
            } else {
              o.values.push_back(v.text);
            }
            break;
          case Node::integer:
          case Node::real:
            o.values.push_back(v.text);
            break;
          case Node::array:
            for (const Node& item : v.items) {
              if (item.kind != Node::string && item.kind != Node::integer && item.kind != Node::real) {
                fail(path, item.line, ok + ": expected an array of strings or numbers");
              }
              o.values.push_back(item.text);
            }
            if (o.values.empty()) fail(path, v.line, ok + ": empty array");
            break;
          default:
            fail(path, v.line, ok + ": expected a string, number, boolean or array, found " + kind_name(v.kind));
        }
        j.options.push_back(std::move(o));
      }
    }
    r.jobs.push_back(std::move(j));
  }
  return r;
}

}  // namespace texproc::cli
