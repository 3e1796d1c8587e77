model tri.obj

camera 0 0 0 target 0 0 0
