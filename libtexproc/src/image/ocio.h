// OpenColorIO glue: the only file that includes OpenColorIO.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace texproc {

// A pair of CPU processors between one named color space and the active
// config's scene_linear role. Thread-safe after creation.
class OcioTransform {
 public:
  // Throws Error{bad_arguments} naming the space and listing the valid names,
  // or Error{invalid_file} if $OCIO names a config that cannot be loaded.
  static std::shared_ptr<const OcioTransform> create(const std::string& space);
  // Color space names (and aliases) of the active config.
  static std::vector<std::string> names();

  // In place on `width` pixels of `channels` (1-4; gray goes through as R=G=B,
  // alpha is untouched).
  virtual void to_linear(float* pixels, int channels, int width) const = 0;
  virtual void from_linear(float* pixels, int channels, int width) const = 0;
  virtual const std::string& config_path() const = 0;
  virtual ~OcioTransform() = default;
};

}  // namespace texproc
