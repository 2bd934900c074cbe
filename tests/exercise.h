// tests/exercise.h -- one input, every reader: what the fuzzer runs and `make test` replays.
#ifndef RT_EXERCISE_H
#define RT_EXERCISE_H

#include "../ray.h"

// Reads `text` as a scene file; if it reads, renders it at 4 x 4 and probes every line of the
// text as a probe line. Returns false with *why if anything is wrong: an error message without
// the file and line, or a colour that is not finite.
bool ExerciseSceneText(const std::string &text, std::string *why);

#endif
