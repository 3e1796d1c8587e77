model tri.obj
light 1 1 1
model tri.obj bogus 1
