// Writing a world as a scene file: a WorldDef built in code becomes a TOML scene that loads back
// to the same definition, so `fixstep replay` and `fixstep render --replay`
// work for worlds that never had a scene file. See README "Scene format", "Writing a scene".
#pragma once

#include <filesystem>
#include <string>

#include "fixstep/core/world.hpp"
#include "fixstep/core/world_def.hpp"

namespace fixstep {

/// `def` as the text of a scene file that parse_scene() reads back to the same definition:
/// equal definition_hash (recording.hpp), and every number bit for bit (each written as the
/// shortest decimal that reads back as the same double, always as a TOML float so -0.0 keeps
/// its sign). Every body becomes a [[body]] table and every link a [[spring]] table, in order,
/// so body i and link i keep their indices; generators are not reconstructed. Every segment
/// becomes a [[segment]] table, in order (a polyline's segments with their ghost vertices as
/// prev and next), one a kinematic body carries with `body` = that body's name. Every joint
/// becomes a [[joint]] table, in order, its bodies by name (none for the world).
///
/// What the format holds differently, documented and tested:
///   - names: every body is written with a name, and links name their bodies by it. A name is
///     kept when it is non-empty and its first use; an empty name becomes "body<i>" (the
///     loader's default), and a repeated one gets "~2", "~3", ... (the first free), since scene
///     names are unique.
///   - appearance: a body with a Collider is written as a disc (`radius`), so one without an
///     Appearance reloads with Appearance{collider radius, default colour}; an Appearance whose
///     radius differs from the collider's (or with no collider, from 0.5 m) is `draw_radius`.
///   - not written, as they change no state and the hash leaves them out: settings.threads
///     (reloads as 0, automatic) and settings.track_dissipation (a scene keeps the account:
///     true). flush_denormals is written only when false, allow_unstable only when true
///     (World(def) then warns instead of refusing; the hash leaves it out). The contacts'
///     sleep_speed and sleep_time are written only with sleep on, and only when not the
///     defaults: with sleep off they do nothing, the hash leaves them out, and they reload as
///     the defaults.
///   - joints: the anchor and the axis are always written where the type uses them (the
///     loader's defaults are the bodies' positions); a distance joint's anchor_b always, an
///     unset one as the anchor; one equal to its anchor (bit for bit) reloads unset (the same
///     joint: unset means the anchor).
///
/// Throws std::invalid_argument, "format_scene: WHERE: WHY", when `def` cannot be written so
/// that it loads back exactly: a link naming a body that is not one of def's or one body twice; a
/// segment carried by a body that is not one of def's or not kinematic; a joint's body that is
/// neither null (the world) nor one of def's; a
/// static or kinematic body with a mass other than the default 1 kg, a spring, constant force,
/// gravity or drag (a scene gives such bodies none), or a static body with a non-zero
/// velocity; a plane normal that the loader's normalisation (n/|n|) would change (a normal
/// not of unit length; axis-aligned unit normals are always fine); more than max_scene_bytes
/// of text; and any value the loader refuses (its SceneError message follows: a non-finite
/// number, mass <= 0, dt outside (0, 1] s, a negative stiffness, a name that is not valid
/// UTF-8, a number beyond float range with precision f32, discs overlapping at the start
/// with contacts on, ...), as format_scene parses the text back and compares the hashes
/// before returning it. A text that loads with another hash throws std::logic_error (a bug of
/// the writer, never expected).
[[nodiscard]] std::string format_scene(const WorldDef& def);

/// Writes format_scene(def) to `file` atomically (a temporary file beside it, then a rename):
/// `file` is never left partial and no temporary file stays behind. Throws std::invalid_argument
/// as format_scene (nothing is written), and std::runtime_error "cannot write FILE: REASON"
/// (the system's reason, e.g. "Permission denied", or that the directory does not exist) when
/// the file cannot be written.
void write_scene(const std::filesystem::path& file, const WorldDef& def);

/// For programs that build their world in code and record a session: writes def's scene
/// beside the recording about to be written to `recording_file` (write_scene, at
/// `recording_file` with its extension replaced by ".scene.toml": "out/session.rec" ->
/// "out/session.scene.toml") and returns the scene's file name alone ("session.scene.toml")
/// to give Recorder as its scene. `fixstep replay out/session.rec` and `fixstep render
/// --replay out/session.rec` then find the scene beside the recording (a relative scene path
/// is looked up in the current directory first, then beside the recording). Throws as
/// write_scene. A recording can also carry the scene itself, needing no file:
/// Recorder(def, label, hash_every, format_scene(def)).
std::string write_scene_beside(const std::filesystem::path& recording_file, const WorldDef& def);

}  // namespace fixstep
