"""Prints the cache key of a scene spec for scripts/bench_pbr.sh: <name>-<hash of the resolved
spec and of the generator's scripts>, so a changed spec or generator renders anew.
  /usr/bin/python3 scripts/pbr/spec_key.py configs/pbr/bunny_plastic.json [--set k=v ...]
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import pbr_common as pc  # noqa: E402

args = sys.argv[1:]
sets = [args[i + 1] for i in range(1, len(args) - 1) if args[i] == "--set"]
spec = pc.load_spec(args[0], sets)
here = os.path.dirname(os.path.abspath(__file__))
# The generator's own files only (not this script or the bench table printer).
scripts = [os.path.join(here, n) for n in ("pbr_common.py", "render_blender.py", "postprocess.py")]
print(f"{spec['name']}-{pc.spec_hash(spec, scripts)}")
