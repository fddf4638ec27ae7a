// The NumPy shape checks every binder shares, so a wrong array gets the same message everywhere.
#include "bindings.h"

namespace phongcl::python {

std::string shape_of(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) text += (d ? ", " : "") + std::to_string(array.shape(d));
  return text + (array.ndim() == 1 ? ",)" : ")");
}

void require_shape(const py::array& array, const std::string& name, py::ssize_t height, py::ssize_t width,
                   int channels) {
  const bool ok = channels == 1 ? array.ndim() == 2 && array.shape(0) == height && array.shape(1) == width
                                : array.ndim() == 3 && array.shape(0) == height && array.shape(1) == width &&
                                      array.shape(2) == channels;
  if (!ok)
    throw py::value_error(name + " must have shape (" + std::to_string(height) + ", " + std::to_string(width) +
                          (channels == 1 ? "" : ", " + std::to_string(channels)) + "), got " + shape_of(array));
}

}  // namespace phongcl::python
