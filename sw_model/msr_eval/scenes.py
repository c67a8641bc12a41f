"""The evaluation's scene set: the renderer's built-in scenes (msr_model.embree.scene_names)
and these Debian-packaged model files, the textured ones among them, and the id a scene goes
by in records, caches and tables."""
from __future__ import annotations

from msr_model.scenes import scene_id  # noqa: F401  (the one definition; used from here too)

# Debian-packaged real models (glmark2-data, assimp-testmodels) used besides the built-ins.
MODEL_FILES = [
    "/usr/share/glmark2/models/horse.3ds",
    "/usr/share/glmark2/models/cat.3ds",
    "/usr/share/glmark2/models/asteroid-high.3ds",
    "/usr/share/assimp/models/OBJ/WusonOBJ.obj",
    # textured (besides the built-in duck and teapots): OBJ + .mtl + JPEG, glTF 1.0, glTF 2.0
    "/usr/share/assimp/models/OBJ/spider.obj",
    "/usr/share/assimp/models/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf",
    "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf",
]
# Scenes whose surfaces carry diffuse textures (scene ids), reported on their own.
TEXTURED_SCENES = ("duck", "teapots", "spider", "CesiumMilkTruck", "BoxTextured")
