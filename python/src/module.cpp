// texproc's Python extension, texproc._texproc: the module, its exceptions,
// and the parts each binding file adds.
#include <pybind11/pybind11.h>

#include <string>

#include "bindings.h"
#include "texproc/error.h"
#include "texproc/runtime.h"
#include "texproc/version.h"

namespace texproc::py_binding {
namespace {

// The exception classes, made once in the module (texproc.Error and one
// subclass a code; the subclasses also derive from the built-in exception a
// Python caller would catch for that kind of failure).
struct Exceptions {
  PyObject* base = nullptr;
  PyObject* bad_arguments = nullptr;
  PyObject* io = nullptr;
  PyObject* invalid_file = nullptr;
  PyObject* unsupported = nullptr;
};
Exceptions exceptions;

PyObject* new_exception(py::module_& m, const char* name, const char* doc, py::tuple bases) {
  const std::string qualified = std::string("texproc.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!cls) throw py::error_already_set();
  m.add_object(name, py::handle(cls));
  return cls;
}

void make_exceptions(py::module_& m) {
  exceptions.base = new_exception(m, "Error",
                                  "Base of texproc's errors. `code` is the texproc CLI's exit code for the failure "
                                  "(1 bad arguments, 2 I/O, 3 invalid file, 4 runtime, 5 unsupported).",
                                  py::make_tuple(py::handle(PyExc_Exception)));
  const py::handle base(exceptions.base);
  exceptions.bad_arguments = new_exception(m, "BadArgumentsError", "An argument or option is invalid.",
                                           py::make_tuple(base, py::handle(PyExc_ValueError)));
  exceptions.io = new_exception(m, "IoError", "A file could not be opened, read or written.",
                                py::make_tuple(base, py::handle(PyExc_OSError)));
  exceptions.invalid_file =
      new_exception(m, "InvalidFileError", "A file was read but its contents are invalid.", py::make_tuple(base));
  exceptions.unsupported =
      new_exception(m, "UnsupportedError", "Valid, but texproc does not support it.", py::make_tuple(base));
}

void raise(const Error& e) {
  PyObject* cls = exceptions.base;
  switch (e.code()) {
    case ErrorCode::bad_arguments:
      cls = exceptions.bad_arguments;
      break;
    case ErrorCode::io:
      cls = exceptions.io;
      break;
    case ErrorCode::invalid_file:
      cls = exceptions.invalid_file;
      break;
    case ErrorCode::unsupported:
      cls = exceptions.unsupported;
      break;
    default:
      break;
  }
  py::object instance = py::reinterpret_steal<py::object>(PyObject_CallFunction(cls, "s", e.what()));
  if (!instance) return;  // the call set its own error
  instance.attr("code") = int(e.code());
  PyErr_SetObject(cls, instance.ptr());
}

// Limits the library's threads inside a `with` block.
class ThreadLimitContext {
 public:
  explicit ThreadLimitContext(int threads) : threads_(threads) {}
  void enter() { limit_ = std::make_unique<ThreadLimit>(threads_); }
  void exit(const py::args&) { limit_.reset(); }

 private:
  int threads_;
  std::unique_ptr<ThreadLimit> limit_;
};

}  // namespace
}  // namespace texproc::py_binding

PYBIND11_MODULE(_texproc, m) {
  using namespace texproc;
  using namespace texproc::py_binding;
  m.doc() = "texproc: texture processing (mip chains, block compression, normal and cone maps, SATs, cube maps).";
  make_exceptions(m);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      raise(e);
    }
  });
  m.attr("__version__") = version_string();
  m.attr("version_info") = py::make_tuple(TEXPROC_VERSION_MAJOR, TEXPROC_VERSION_MINOR, TEXPROC_VERSION_PATCH);
  m.def("hardware_threads", &hardware_threads, "Hardware threads available to this process.");
  m.def("thread_limit", &thread_limit, "Threads texproc's work may use now.");
  m.def("simd_target", &simd_target_name, "The SIMD target the kernels use (\"scalar\" when forced).");
  py::class_<ThreadLimitContext>(m, "threads",
                                 "with texproc.threads(n): texproc's work in the block uses at most n threads (0: "
                                 "all). Output bytes never depend on it.")
      .def(py::init<int>(), py::arg("count"))
      .def("__enter__", [](ThreadLimitContext& self) { self.enter(); })
      .def("__exit__", &ThreadLimitContext::exit);
  bind_images(m);
  bind_textures(m);
  bind_maps(m);
  bind_cubemaps(m);
}
