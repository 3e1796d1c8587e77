model tri.obj
background 1 2 300
