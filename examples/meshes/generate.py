"""Writes the committed .msh files from the .geo files beside this script.

Run with the Gmsh Python API (`pip install gmsh`): python3 examples/meshes/generate.py
The project never needs Gmsh to build or test: the .msh files are committed.
"""
import os
import gmsh

HERE = os.path.dirname(os.path.abspath(__file__))
SCENES = os.path.join(HERE, "..", "scenes")


def write(geo, out, version=4.1, binary=False, numbers=None):
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    path = os.path.join(HERE, geo)
    if numbers:
        # the .geo reads its parameters with `If (!Exists(n)) n = ...; EndIf`
        with open(path) as f:
            text = f.read()
        path = os.path.join(HERE, "_parameters.geo")
        with open(path, "w") as f:
            f.write("".join(f"{k} = {v};\n" for k, v in numbers.items()) + text)
    gmsh.open(path)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.MshFileVersion", version)
    gmsh.option.setNumber("Mesh.Binary", 1 if binary else 0)
    gmsh.write(out)
    gmsh.finalize()
    if numbers:
        os.remove(path)


for n in (4, 8, 16, 32, 64):
    write("unit_square.geo", os.path.join(HERE, f"unit_square_{n}.msh"), numbers={"n": n})
write("unit_square.geo", os.path.join(HERE, "unit_square_8_binary.msh"), binary=True, numbers={"n": 8})
write("unit_square.geo", os.path.join(HERE, "unit_square_8_v22.msh"), version=2.2, numbers={"n": 8})
for geo in ("bimaterial_strip", "notched_block", "o_ring"):
    if os.path.exists(os.path.join(HERE, geo + ".geo")):
        write(geo + ".geo", os.path.join(HERE, geo + ".msh"))
# the plane family's envelope meshes: a slanted block with a hole, ~400, ~4 000 and ~7 500 nodes
write("holed_block.geo", os.path.join(HERE, "holed_block.msh"), numbers={"h": 0.3})
write("holed_block.geo", os.path.join(HERE, "holed_block_4k.msh"), numbers={"h": 0.084})
write("holed_block.geo", os.path.join(HERE, "holed_block_8k.msh"), numbers={"h": 0.06})
