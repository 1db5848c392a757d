#include "json.h"

#include <json/writer.h>

#include <memory>
#include <sstream>

namespace texproc::cli {
namespace {

class JsonPrinter {
 public:
  explicit JsonPrinter(int digits) {
    Json::StreamWriterBuilder b;
    b["indentation"] = "";
    b["precision"] = digits;
    b["emitUTF8"] = true;
    scalar_.reset(b.newStreamWriter());
  }

  void print(const Json::Value& v, int depth) {
    if (v.isObject() && !v.empty()) {
      out_ += "{\n";
      const Json::Value::Members keys = v.getMemberNames();
      for (std::size_t k = 0; k < keys.size(); ++k) {
        indent(depth + 1);
        print_scalar(Json::Value(keys[k]));
        out_ += ": ";
        print(v[keys[k]], depth + 1);
        out_ += k + 1 < keys.size() ? ",\n" : "\n";
      }
      indent(depth);
      out_ += "}";
    } else if (v.isArray() && !v.empty()) {
      if (holds_containers(v)) {
        out_ += "[\n";
        for (Json::ArrayIndex i = 0; i < v.size(); ++i) {
          indent(depth + 1);
          print(v[i], depth + 1);
          out_ += i + 1 < v.size() ? ",\n" : "\n";
        }
        indent(depth);
        out_ += "]";
      } else {
        out_ += "[";
        for (Json::ArrayIndex i = 0; i < v.size(); ++i) {
          if (i) out_ += ", ";
          print_scalar(v[i]);
        }
        out_ += "]";
      }
    } else if (v.isObject()) {
      out_ += "{}";
    } else if (v.isArray()) {
      out_ += "[]";
    } else {
      print_scalar(v);
    }
  }

  std::string take() { return std::move(out_); }

 private:
  static bool holds_containers(const Json::Value& array) {
    for (const Json::Value& e : array) {
      if (e.isObject() || e.isArray()) return true;
    }
    return false;
  }
  void indent(int depth) { out_.append(std::size_t(2 * depth), ' '); }
  void print_scalar(const Json::Value& v) {
    std::ostringstream s;
    scalar_->write(v, &s);
    out_ += s.str();
  }

  std::unique_ptr<Json::StreamWriter> scalar_;
  std::string out_;
};

}  // namespace

std::string to_json(const Json::Value& v, int digits) {
  JsonPrinter p(digits);
  p.print(v, 0);
  return p.take();
}

}  // namespace texproc::cli
