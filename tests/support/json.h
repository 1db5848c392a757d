// JSON documents in the CLI's tests: --json summaries, info, actions.
#pragma once

#include <gtest/gtest.h>
#include <json/reader.h>
#include <json/value.h>

#include <memory>
#include <string>

namespace texproc::test {

// Parses `text`; a failure is a test failure naming the error and the text.
inline Json::Value parse_json(const std::string& text) {
  Json::CharReaderBuilder b;
  std::unique_ptr<Json::CharReader> reader(b.newCharReader());
  Json::Value v;
  std::string errors;
  EXPECT_TRUE(reader->parse(text.data(), text.data() + text.size(), &v, &errors)) << errors << "\n" << text;
  return v;
}

// A small OpenColorIO config with two spaces of its own: gamma22 (also a
// name in texproc's built-in config) and curve22 (only here), to show that
// the config a run read is listed as a dependency and is what resolved the
// name.
inline constexpr const char* kTestOcioConfig = R"(ocio_profile_version: 2
roles:
  default: lin
  scene_linear: lin
file_rules:
  - !<Rule> {name: Default, colorspace: default}
displays:
  sRGB:
    - !<View> {name: Raw, colorspace: lin}
colorspaces:
  - !<ColorSpace>
    name: lin
  - !<ColorSpace>
    name: gamma22
    to_scene_reference: !<ExponentTransform> {value: 2.2}
  - !<ColorSpace>
    name: curve22
    to_scene_reference: !<ExponentTransform> {value: 2.2}
)";

}  // namespace texproc::test
