// Source file of the accelerators in the bad-spec catalogue (only its existence matters).
void QuaternionToEuler() {}
