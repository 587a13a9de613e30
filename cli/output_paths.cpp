// The paths of each fixstep command, for the checks of fixstep/io/output_paths.hpp.
#include "output_paths.hpp"

#include <filesystem>
#include <fixstep/capture/manifest.hpp>

#include "capture_sink.hpp"

namespace fixstep::cli {

CommandPaths run_paths(const RunOptions& o) {
  CommandPaths c;
  c.program = "fixstep run";
  c.inputs = {{"SCENE", o.scene.scene}};
  if (o.input) c.inputs.push_back({"--input", *o.input});
  if (o.csv) c.outputs.push_back({"--csv", *o.csv});
  if (o.record) c.outputs.push_back({"--record", *o.record});
  return c;
}

namespace {
/// --out DIR's manifest and --video FILE with its manifest.
void add_capture_outputs(CommandPaths& c, const std::optional<std::string>& out,
                         const std::optional<std::string>& video) {
  if (out) {
    c.capture_dir = out;
    c.outputs.push_back(
        {"--out DIR's manifest", (std::filesystem::path(*out) / "frames.csv").string()});
  }
  if (video) {
    c.outputs.push_back({"--video", *video});
    if (const auto manifest = beside_video(*video, ".frames.csv")) {
      c.outputs.push_back({"--video's manifest", manifest->string()});
    }
  }
}
}  // namespace

CommandPaths render_paths(const RenderOptions& o, const std::string& scene) {
  CommandPaths c;
  c.program = "fixstep render";
  c.inputs = {{"SCENE", scene}};
  c.overwrite = o.overwrite;
  if (o.replay) c.inputs.push_back({"--replay", *o.replay});
  add_capture_outputs(c, o.out, o.video);
  return c;
}

CommandPaths compare_paths(const CompareOptions& o) {
  CommandPaths c;
  c.program = "fixstep compare";
  c.inputs = {{"SCENE", o.scene}};
  c.overwrite = o.overwrite;
  add_capture_outputs(c, o.out, o.video);
  if (const auto csv = summary_path(o))
    c.outputs.push_back({o.csv   ? "--csv"
                         : o.out ? "--out DIR's summary"
                                 : "--video's summary",
                         csv->string()});
  return c;
}

CommandPaths view_paths(const ViewOptions& o) {
  CommandPaths c;
  c.program = "fixstep view";
  c.inputs = {{"SCENE", o.scene.scene}};
  if (o.record) c.outputs.push_back({"--record", *o.record});
  return c;
}

}  // namespace fixstep::cli
