model missing.obj
