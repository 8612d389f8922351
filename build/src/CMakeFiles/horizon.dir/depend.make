# Empty dependencies file for horizon.
# This may be replaced when dependencies are built.
