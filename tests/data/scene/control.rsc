model tri.obj
frobnicate [31mred
