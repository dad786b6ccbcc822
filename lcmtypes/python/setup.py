"""Builds the package `hkf` from the message definitions in the folder above
with lcm-gen (PyPI lcm) when the wheel is built; the generated code goes to
build/generated here (ignored by git)."""
import glob
import os
import subprocess
import sys

import lcm
from setuptools import setup

HERE = os.path.dirname(os.path.abspath(__file__))
GENERATED = os.path.join("build", "generated")

definitions = sorted(glob.glob(os.path.join(HERE, "..", "*.lcm")))
if not definitions:
    sys.exit("hkf-lcmtypes: no .lcm files in the folder above (install from the hkf repository)")
os.makedirs(os.path.join(HERE, GENERATED), exist_ok=True)
subprocess.run([os.path.join(lcm.LCM_BIN_DIR, "lcm-gen"), "--python", "--ppath", os.path.join(HERE, GENERATED),
                *definitions], check=True)

setup(packages=["hkf"], package_dir={"": GENERATED})
