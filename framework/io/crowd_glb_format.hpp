#pragma once
// The layout of a crowdlab crowd file (.glb, glTF 2.0 binary), shared by write_crowd_glb and
// read_crowd_glb. Readers other than crowdlab (Blender, three.js, the Khronos validator) see a plain
// glTF scene with skinned, animated characters; crowdlab's own data rides in `extras`.
//
// Scene root nodes, in this order:
//   per character c (in crowd order):
//     node "<name>"          extras {"crowdlab_character": {...}}, identity transform; its only child is
//                            the pelvis joint node. Holds the body shape:
//                              name, palette, sex ("female"/"male"), height_m, girth,
//                              joint_offsets_m [24][3], capsules [24]{a[3], b[3], radius_m},
//                              rest_contact_pairs [[i, j], ...],
//                              body_mesh: true when the character carries its own skinned surface
//       24 joint nodes named after the SMPL joints ("pelvis", ..., "right_hand"), nested as
//       kJointParent says; rest TRS: translation = joint offset, no rotation (the T-pose).
//     node "<name>_body"     mesh + skin, in the bind (rest) pose; the skin's inverseBindMatrices undo
//                            the rest-pose joint positions. Either one low-poly capsule per bone, rigidly
//                            skinned (weight 1) to its bone (procedural bodies), or, with body_mesh, the
//                            character's SkinnedMesh: POSITION, NORMAL (unit), JOINTS_0 (u8 x 4),
//                            WEIGHTS_0 (float x 4, sum 1), uint32 indices; indices/JOINTS_0/WEIGHTS_0
//                            accessors are shared by characters whose meshes have the same topology.
//   node "ground"            extras {"crowdlab_environment": "ground"}: a quad at y = 0 (if ground_plane)
//   node "box_<k>"           extras {"crowdlab_environment": "box"}: the shared unit cube [-1, 1]^3
//                            scaled by half_extents, rotated and translated to the box
//   node "<mesh name>"       extras {"crowdlab_environment": "mesh"}: a triangle mesh in world metres
// scene.extras {"crowdlab": {format, fps, seed (decimal text: 64 bits do not fit a JSON double),
//                            condition_id, scenario}}
// One animation "crowd": for every character, a LINEAR rotation channel for each of the 24 joints and
// a LINEAR translation channel for the pelvis (world root position); key times are f / fps seconds.
// Rotations are made sign-continuous frame to frame (q and -q are the same rotation) so that
// interpolating viewers do not spin the long way round.
namespace crowdlab {

inline constexpr int kCrowdGlbFormat = 1;
inline constexpr const char* kCharacterExtrasKey = "crowdlab_character";
inline constexpr const char* kEnvironmentExtrasKey = "crowdlab_environment";
inline constexpr const char* kSceneExtrasKey = "crowdlab";

}  // namespace crowdlab
