# a scene using every statement
model ../../tests/data/scene/tri.obj at 1 2 3 rotate 0 90 0 scale 2
model "../../tests/data/scene/tri.obj" scale 1 2 3 kd 0.5 0.25 1   # same file: loaded once
light 0 1 0
light 1 0 0 0.5 0.5 0.5
camera 0 0 5 target 0 0 0 fov 40
background 10 20 30
