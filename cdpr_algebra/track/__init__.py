"""Following the robot's equilibrium while its cables move: slack and taut switches, folds and jumps."""
