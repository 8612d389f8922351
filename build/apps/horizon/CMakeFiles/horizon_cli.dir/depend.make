# Empty dependencies file for horizon_cli.
# This may be replaced when dependencies are built.
