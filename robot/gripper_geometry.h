#pragma once
/// @file
/// The parallel-jaw gripper's dimensions as the robot layer knows them (they must match
/// models/gripper/gripper_body.inc.xml; tests/models checks that they do).
/// Flange frame F: z along the tool; the fingers close along y_F.

namespace sortcell::robot {

/// The TCP (between the finger pads' centres) lies this far along z_F from the flange (m).
inline constexpr double kTcpOffsetZ = 0.185;
/// Largest gap between the pads (m); the finger joint is the half-gap, 0 .. kMaxGap / 2.
inline constexpr double kMaxGap = 0.110;
/// The finger tips reach this far beyond the TCP along z_F (m).
inline constexpr double kFingerTipBeyondTcp = 0.018;
/// The palm's lowest point lies this far before the TCP along z_F (m): an object may reach this far
/// up between the fingers.
inline constexpr double kPalmBeforeTcp = 0.082;
/// The palm seen from above: it reaches this far to either side of the TCP along the closing
/// direction and this far across it (m). Lower than a neighbour's top, it pushes the neighbour over.
inline constexpr double kPalmHalfLength = 0.088;
inline constexpr double kPalmHalfWidth = 0.018;
/// Above the palm, the housing (and the narrower wrist above it): a column this wide around the TCP's
/// axis, its lowest point this far before the TCP along z_F (m).
inline constexpr double kHousingRadius = 0.042;
inline constexpr double kHousingBeforeTcp = 0.113;
/// The gripper as the cell's camera-occlusion check sees it: a capsule this wide around the flange's
/// axis, from the flange to the finger tips (m).
inline constexpr double kGripperEnvelopeRadius = 0.075;
/// Each finger seen from above: from its pad's face it reaches this far outwards along the closing
/// direction (the stem behind the pad) and this far to either side across it (m).
inline constexpr double kFingerDepth = 0.030;
inline constexpr double kFingerHalfWidth = 0.020;
/// Each finger is a position servo with this stiffness (N/m), its force limited to kFingerForceLimit (N).
inline constexpr double kFingerServoKp = 2000;
inline constexpr double kFingerForceLimit = 60;
/// The pads' sliding and torsional friction (their MJCF class gripper_pad; priority 1, so theirs is
/// every pad contact's friction).
inline constexpr double kPadFriction = 1.5;
inline constexpr double kPadTwistFriction = 0.02;

/// The hand-eye calibration marker: an ArUco marker (OpenCV's 4x4_50 dictionary) printed on a plate
/// on the housing's +x_F side, facing +x_F, its centre at (kMarkerFaceX, 0, kMarkerCentreZ) in the
/// flange frame (m); the black square is kMarkerSide wide (m).
inline constexpr int kMarkerId = 7;
inline constexpr double kMarkerSide = 0.056;
inline constexpr double kMarkerFaceX = 0.046;
inline constexpr double kMarkerCentreZ = 0.037;

}  // namespace sortcell::robot
