model tri.obj
sky a.png b.png
