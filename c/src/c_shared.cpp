// libfluid_c.so: the objects of fluid_c, whole (c/CMakeLists.txt); nothing of its own.
