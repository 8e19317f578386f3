"""The robot and its statics: robot files and validation, poses and rotations, equilibrium equations per taut set, stability (reduced Hessian), input errors."""
