model ../../tests/data/scene/tri.obj at 1 2 3 kd 0 0 1
sky procedural
light 1 1 1 1 0 0
