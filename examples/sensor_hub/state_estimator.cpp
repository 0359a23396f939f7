// A one-sample state estimator on an IMU reading (SensorHub.yaml): the attitude and body rates
// as measured, the linear acceleration with gravity removed (the quaternion rotates the world's
// g into the body frame), each with its 3 x 3 covariance in its block of the 6 x 6 one; the
// force on a body of MASS_KG, the point one metre down along gravity, and a rate-damping
// command. The structs and the declaration come from StateEstimator_messages.h, which rfc
// writes from the ports' messages (`rfc stub SensorHub.yaml StateEstimator --lang hls`).
#include "StateEstimator_messages.h"

static const double GRAVITY = 9.80665;  // m/s^2, standard
static const double MASS_KG = 1.5;
static const double DAMPING = 0.5;  // command = -DAMPING * angular velocity

// Copy a 3 x 3 row-major covariance into the block of a 6 x 6 one starting at (first, first).
static void place(const double small[9], double big[36], int first) {
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) {
            big[(first + row) * 6 + first + col] = small[row * 3 + col];
        }
    }
}

void StateEstimator(imu_t imu, pose_t *pose, twist_t *twist, accel_t *accel, wrench_t *wrench,
                    contact_t *contact, command_t *command) {
#pragma HLS INTERFACE mode=ap_ctrl_hs port=return
#pragma HLS DISAGGREGATE variable=imu
#pragma HLS INTERFACE mode=ap_none port=imu
#pragma HLS DISAGGREGATE variable=pose
#pragma HLS INTERFACE mode=ap_vld port=pose
#pragma HLS DISAGGREGATE variable=twist
#pragma HLS INTERFACE mode=ap_vld port=twist
#pragma HLS DISAGGREGATE variable=accel
#pragma HLS INTERFACE mode=ap_vld port=accel
#pragma HLS DISAGGREGATE variable=wrench
#pragma HLS INTERFACE mode=ap_vld port=wrench
#pragma HLS DISAGGREGATE variable=contact
#pragma HLS INTERFACE mode=ap_vld port=contact
#pragma HLS DISAGGREGATE variable=command
#pragma HLS INTERFACE mode=ap_vld port=command
    const double x = imu.orientation.x, y = imu.orientation.y, z = imu.orientation.z;
    const double w = imu.orientation.w;
    // the world's down axis in the body frame: the third row of the rotation matrix
    const double down_x = 2 * (x * z - w * y), down_y = 2 * (y * z + w * x);
    const double down_z = 1 - 2 * (x * x + y * y);

    double pose_covariance[36] = {0}, twist_covariance[36] = {0}, accel_covariance[36] = {0};
    place(imu.orientation_covariance, pose_covariance, 3);
    place(imu.angular_velocity_covariance, twist_covariance, 3);
    place(imu.linear_acceleration_covariance, accel_covariance, 0);

    pose->pose.position.x = 0;
    pose->pose.position.y = 0;
    pose->pose.position.z = 0;
    pose->pose.orientation.x = x;
    pose->pose.orientation.y = y;
    pose->pose.orientation.z = z;
    pose->pose.orientation.w = w;
    twist->twist.linear.x = 0;
    twist->twist.linear.y = 0;
    twist->twist.linear.z = 0;
    twist->twist.angular.x = imu.angular_velocity.x;
    twist->twist.angular.y = imu.angular_velocity.y;
    twist->twist.angular.z = imu.angular_velocity.z;
    accel->accel.linear.x = imu.linear_acceleration.x - GRAVITY * down_x;
    accel->accel.linear.y = imu.linear_acceleration.y - GRAVITY * down_y;
    accel->accel.linear.z = imu.linear_acceleration.z - GRAVITY * down_z;
    accel->accel.angular.x = 0;
    accel->accel.angular.y = 0;
    accel->accel.angular.z = 0;
    for (int k = 0; k < 36; ++k) {
        pose->covariance[k] = pose_covariance[k];
        twist->covariance[k] = twist_covariance[k];
        accel->covariance[k] = accel_covariance[k];
    }
    wrench->force.x = MASS_KG * accel->accel.linear.x;
    wrench->force.y = MASS_KG * accel->accel.linear.y;
    wrench->force.z = MASS_KG * accel->accel.linear.z;
    wrench->torque.x = 0;
    wrench->torque.y = 0;
    wrench->torque.z = 0;
    contact->x = down_x;
    contact->y = down_y;
    contact->z = down_z;
    command->linear.x = 0;
    command->linear.y = 0;
    command->linear.z = 0;
    command->angular.x = -DAMPING * imu.angular_velocity.x;
    command->angular.y = -DAMPING * imu.angular_velocity.y;
    command->angular.z = -DAMPING * imu.angular_velocity.z;
}
