// The other topics of a drive, beside its lidar, for the fixtures that test that `segment --format
// mcap` keeps a drive whole: an IMU at 100 Hz and a GNSS receiver at 10 Hz over the frames' span,
// serialized to CDR by @foxglove/rosmsg2-serialization (not by lpir-gseg's code), and the
// metadata record and attachment an MCAP recorder may add.
//
// For `frames` lidar frames (stamps stampNs(0) .. stampNs(frames - 1), 100 ms apart):
//   /imu/data  sensor_msgs/msg/Imu, 10 per frame period, k = 0..10 x frames - 1: stamp
//              stampNs(0) + k x 10 ms, frame_id "imu_link", orientation (0, 0, sin(k/200),
//              cos(k/200)), angular_velocity (0, 0, 0.01 k), linear_acceleration (0.1, 0, 9.81),
//              covariances 0 but the diagonal 0.01;
//   /gps/fix   sensor_msgs/msg/NavSatFix, one per frame at its stamp + 5 ms, frame_id "gps",
//              status 0 (fix) service 1 (GPS), latitude 48.1 + i x 1e-6, longitude 11.5,
//              altitude 520.25, covariance type 2 (diagonal known).
import { parse } from "@foxglove/rosmsg";
import { MessageWriter } from "@foxglove/rosmsg2-serialization";

import { stampNs } from "./pointcloud.mjs";

const SEPARATOR = "=".repeat(80);
const HEADER_DEPENDENCIES = [
  SEPARATOR,
  "MSG: std_msgs/Header",
  "builtin_interfaces/Time stamp",
  "string frame_id",
  SEPARATOR,
  "MSG: builtin_interfaces/Time",
  "int32 sec",
  "uint32 nanosec",
];

export const IMU_TYPE = "sensor_msgs/msg/Imu";
export const IMU_DEFINITION = [
  "std_msgs/Header header",
  "geometry_msgs/Quaternion orientation",
  "float64[9] orientation_covariance",
  "geometry_msgs/Vector3 angular_velocity",
  "float64[9] angular_velocity_covariance",
  "geometry_msgs/Vector3 linear_acceleration",
  "float64[9] linear_acceleration_covariance",
  ...HEADER_DEPENDENCIES,
  SEPARATOR,
  "MSG: geometry_msgs/Quaternion",
  "float64 x",
  "float64 y",
  "float64 z",
  "float64 w",
  SEPARATOR,
  "MSG: geometry_msgs/Vector3",
  "float64 x",
  "float64 y",
  "float64 z",
  "",
].join("\n");

export const NAVSATFIX_TYPE = "sensor_msgs/msg/NavSatFix";
export const NAVSATFIX_DEFINITION = [
  "std_msgs/Header header",
  "sensor_msgs/NavSatStatus status",
  "float64 latitude",
  "float64 longitude",
  "float64 altitude",
  "float64[9] position_covariance",
  "uint8 COVARIANCE_TYPE_UNKNOWN = 0",
  "uint8 COVARIANCE_TYPE_APPROXIMATED = 1",
  "uint8 COVARIANCE_TYPE_DIAGONAL_KNOWN = 2",
  "uint8 COVARIANCE_TYPE_KNOWN = 3",
  "uint8 position_covariance_type",
  ...HEADER_DEPENDENCIES,
  SEPARATOR,
  "MSG: sensor_msgs/NavSatStatus",
  "int8 STATUS_NO_FIX = -1",
  "int8 STATUS_FIX = 0",
  "int8 STATUS_SBAS_FIX = 1",
  "int8 STATUS_GBAS_FIX = 2",
  "int8 status",
  "uint16 SERVICE_GPS = 1",
  "uint16 SERVICE_GLONASS = 2",
  "uint16 SERVICE_COMPASS = 4",
  "uint16 SERVICE_GALILEO = 8",
  "uint16 service",
  "",
].join("\n");

const DIAGONAL = [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01];

function header(ns, frameId) {
  return { stamp: { sec: Number(ns / 1000000000n), nanosec: Number(ns % 1000000000n) }, frame_id: frameId };
}

// Every extra message of a drive of `frames` lidar frames, in stamp order: { topic, type,
// definition, stampNs, data (CDR) }.
export function extraMessages(frames) {
  const imu = new MessageWriter(parse(IMU_DEFINITION, { ros2: true }));
  const gps = new MessageWriter(parse(NAVSATFIX_DEFINITION, { ros2: true }));
  const out = [];
  for (let k = 0; k < 10 * frames; ++k) {
    const ns = stampNs(0) + BigInt(k) * 10000000n;
    const data = imu.writeMessage({
      header: header(ns, "imu_link"),
      orientation: { x: 0, y: 0, z: Math.sin(k / 200), w: Math.cos(k / 200) },
      orientation_covariance: DIAGONAL,
      angular_velocity: { x: 0, y: 0, z: 0.01 * k },
      angular_velocity_covariance: DIAGONAL,
      linear_acceleration: { x: 0.1, y: 0, z: 9.81 },
      linear_acceleration_covariance: DIAGONAL,
    });
    out.push({ topic: "/imu/data", type: IMU_TYPE, definition: IMU_DEFINITION, stampNs: ns, data });
  }
  for (let i = 0; i < frames; ++i) {
    const ns = stampNs(i) + 5000000n;
    const data = gps.writeMessage({
      header: header(ns, "gps"),
      status: { status: 0, service: 1 },
      latitude: 48.1 + i * 1e-6,
      longitude: 11.5,
      altitude: 520.25,
      position_covariance: DIAGONAL,
      position_covariance_type: 2,
    });
    out.push({ topic: "/gps/fix", type: NAVSATFIX_TYPE, definition: NAVSATFIX_DEFINITION, stampNs: ns, data });
  }
  return out.sort((a, b) => (a.stampNs < b.stampNs ? -1 : a.stampNs > b.stampNs ? 1 : 0));
}

// The metadata record and the attachment of the MCAP fixtures with extras.
export const EXTRA_METADATA = {
  name: "drive_info",
  metadata: new Map([["vehicle", "test-car-1"], ["route", "fixture loop"]]),
};
export const EXTRA_ATTACHMENT = {
  name: "calibration/lidar_to_imu.yaml",
  mediaType: "application/yaml",
  data: new TextEncoder().encode("translation: [0.1, 0.0, 1.2]\nrotation: [0, 0, 0, 1]\n"),
};
