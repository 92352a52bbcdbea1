//! The robot behind the link: what it holds and how it answers each HFLink request. Board-free
//! and I/O-free: a decoded packet in, the answer packet out.
//!
//! The robot of this example is ideal: what a SET asks for is what the matching READ measures
//! (the speeds, the head and arm states), and the sensors (IMU, GPS, mileage, coordinates)
//! report what the board code stores in their fields. The answers follow the spec's
//! `[session]`: a READ is answered with its reply, a SET or SAVE with the same command back
//! (empty, or carrying `ChassisParameters` for SET_CHASSIS_PARAMETERS), the addresses swapped;
//! before SHAKING_HANDS every other request is answered with an empty SHAKING_HANDS (a refusal).

use crate::hflink::{
    ArmDofVector, ArmParameters, ChassisCoord, ChassisDofVector, ChassisParameters, GpsData,
    HeadParameters, HeadPose, Header, ImuSensorData, Message, MotorParameters, Packet, Request,
    Response, SystemInfo, addresses,
};

/// The robot's state, as the link reads and sets it.
#[derive(Debug, Clone, Default)]
pub struct Robot {
    /// This node's address (a slave's: `0x11` for the MCU).
    pub address: u8,
    /// True once a master's SHAKING_HANDS arrived.
    pub handshaken: bool,
    /// The master's global coordinate, as its handshake carried it.
    pub master_coordinate: ChassisCoord,
    /// What READ_SYSTEM_INFO reports.
    pub system_info: SystemInfo,
    /// The motor parameters last set.
    pub motor_parameters: MotorParameters,
    /// The chassis parameters last set.
    pub chassis_parameters: ChassisParameters,
    /// The head parameters last set.
    pub head_parameters: HeadParameters,
    /// The arm parameters last set.
    pub arm_parameters: ArmParameters,
    /// The speed in the global frame, set and measured.
    pub global_speed: ChassisCoord,
    /// The speed in the robot frame, set and measured.
    pub robot_speed: ChassisCoord,
    /// The speed of each motor, set and measured.
    pub motor_speed: ChassisDofVector,
    /// The mileage of each motor.
    pub motor_mileage: ChassisDofVector,
    /// The coordinate in the global frame.
    pub global_coordinate: ChassisCoord,
    /// The coordinate in the robot frame.
    pub robot_coordinate: ChassisCoord,
    /// The head pose, set and measured.
    pub head_state: HeadPose,
    /// The arm joint positions, set and measured.
    pub arm_state: ArmDofVector,
    /// The raw IMU data.
    pub imu_base: ImuSensorData,
    /// The fused IMU data.
    pub imu_fusion: ImuSensorData,
    /// The GPS fix.
    pub gps: GpsData,
}

impl Robot {
    /// A robot at `address` that reports `system_info`, before its handshake, everything else
    /// zero.
    pub fn new(address: u8, system_info: SystemInfo) -> Self {
        Robot {
            address,
            system_info,
            ..Robot::default()
        }
    }

    /// The answer to `packet`: `None` for a frame that is not a request to this node (a
    /// response, a frame for another node).
    pub fn answer(&mut self, packet: &Packet) -> Option<Packet> {
        let Message::Request(request) = &packet.message else {
            return None;
        };
        let to = packet.header.receiver;
        if to != self.address && to != addresses::BROADCAST {
            return None;
        }
        let response = if self.handshaken || matches!(request, Request::ShakingHands(_)) {
            self.respond(request)
        } else {
            Response::ShakingHands
        };
        Some(Packet {
            header: Header {
                sender: self.address,
                receiver: packet.header.sender,
            },
            message: Message::Response(response),
        })
    }

    /// Carries out `request` and returns its response.
    fn respond(&mut self, request: &Request) -> Response {
        match *request {
            Request::ShakingHands(coordinate) => {
                self.handshaken = true;
                self.master_coordinate = coordinate;
                Response::ShakingHands
            }
            Request::ReadSystemInfo => Response::ReadSystemInfo(self.system_info),
            Request::SetMotorParameters(p) => {
                self.motor_parameters = p;
                Response::SetMotorParameters
            }
            Request::SaveMotorParameters => Response::SaveMotorParameters,
            Request::SetChassisParameters(p) => {
                self.chassis_parameters = p;
                Response::SetChassisParameters(self.chassis_parameters)
            }
            Request::SaveChassisParameters => Response::SaveChassisParameters,
            Request::SetHeadParameters(p) => {
                self.head_parameters = p;
                Response::SetHeadParameters
            }
            Request::SaveHeadParameters => Response::SaveHeadParameters,
            Request::SetArmParameters(p) => {
                self.arm_parameters = p;
                Response::SetArmParameters
            }
            Request::SaveArmParameters => Response::SaveArmParameters,
            Request::SetGlobalSpeed(v) => {
                self.global_speed = v;
                Response::SetGlobalSpeed
            }
            Request::ReadGlobalSpeed => Response::ReadGlobalSpeed(self.global_speed),
            Request::SetRobotSpeed(v) => {
                self.robot_speed = v;
                Response::SetRobotSpeed
            }
            Request::ReadRobotSpeed => Response::ReadRobotSpeed(self.robot_speed),
            Request::SetMotorSpeed(v) => {
                self.motor_speed = v;
                Response::SetMotorSpeed
            }
            Request::ReadMotorSpeed => Response::ReadMotorSpeed(self.motor_speed),
            Request::ReadMotorMileage => Response::ReadMotorMileage(self.motor_mileage),
            Request::ReadGlobalCoordinate => Response::ReadGlobalCoordinate(self.global_coordinate),
            Request::ReadRobotCoordinate => Response::ReadRobotCoordinate(self.robot_coordinate),
            Request::ClearCoordinateData => {
                self.global_coordinate = ChassisCoord::default();
                self.robot_coordinate = ChassisCoord::default();
                Response::ClearCoordinateData
            }
            Request::SetHeadState(pose) => {
                self.head_state = pose;
                Response::SetHeadState
            }
            Request::ReadHeadState => Response::ReadHeadState(self.head_state),
            Request::SetArmState(joints) => {
                self.arm_state = joints;
                Response::SetArmState
            }
            Request::ReadArmState => Response::ReadArmState(self.arm_state),
            Request::ReadImuBaseData => Response::ReadImuBaseData(self.imu_base),
            Request::ReadImuFusionData => Response::ReadImuFusionData(self.imu_fusion),
            Request::ReadGpsData => Response::ReadGpsData(self.gps),
        }
    }
}
