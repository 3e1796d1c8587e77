model tri.obj
sky procedural
light -1 0.2 0
