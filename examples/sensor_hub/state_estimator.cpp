// Stand-in for an HLS state estimator: the DSE example needs only its interface
// (SensorHub.yaml); rfc builds the converters, the manager and the scheduler around it.
void StateEstimator() {}
