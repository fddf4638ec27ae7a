// import phongcl: errors become Python exceptions carrying the command line's one-line messages.
#include "bindings.h"

#include "cl/error_name.h"
#include "cl/opencl.h"
#include "common/error.h"

namespace py = pybind11;

PYBIND11_MODULE(phongcl, module) {
  using namespace phongcl;
  module.doc() =
      "phongcl: deferred Phong shading of G-buffers with OpenCL.\n\n"
      "    scene = phongcl.load_scene('s.json')\n"
      "    gb = phongcl.read_gbuffer('g.exr')\n"
      "    r = phongcl.Relighter(scene, gb)\n"
      "    img = r.shade()                      # float32 (H, W, 4), RGBA\n"
      "    r.set_lights([{'type': 'point', 'position': [3, 4, 5], 'color': [1, 1, 1]}])\n"
      "    phongcl.write_exr('out.exr', r.shade())\n";
  static py::exception<InputError> input_error(module, "InputError", PyExc_ValueError);
  input_error.doc() = "A problem with an input file or value; the message names it (a ValueError).";
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const InputError& e) {
      input_error(e.what());
    } catch (const cl::BuildError& e) {
      std::string message = std::string("kernel build failed: ") + cl_error_name(e.err());
      for (const auto& [device, log] : e.getBuildLog()) message += "\nbuild log:\n" + log;
      PyErr_SetString(PyExc_RuntimeError, message.c_str());
    } catch (const cl::Error& e) {
      PyErr_SetString(PyExc_RuntimeError,
                      (std::string("OpenCL call ") + e.what() + " failed: " + cl_error_name(e.err())).c_str());
    }
  });
  python::bind_scene(module);
  python::bind_gbuffer(module);
  python::bind_images(module);
  python::bind_relighter(module);
}
