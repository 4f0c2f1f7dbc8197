x: lessons/02-barycentric/answer.c src/exercise/student.h src/lesson.h \
 src/raster/raster.h src/scene/scene.h src/raster/raster.h \
 src/scene/texture.h src/trace/trace.h src/shade/shade.h
src/exercise/student.h:
src/lesson.h:
src/raster/raster.h:
src/scene/scene.h:
src/raster/raster.h:
src/scene/texture.h:
src/trace/trace.h:
src/shade/shade.h:
