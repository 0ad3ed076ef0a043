// SPDX-License-Identifier: MIT
/* libFuzzer target: the JSON scene parser (scene_desc_load) on arbitrary bytes. */
#include "fuzz_input.h"

#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("scene.json"));
    fuzz_write(path, data, size);
    SceneDesc desc;
    Error err = {0};
    if (scene_desc_load(path, &desc, &err))
        scene_desc_free(&desc);
    else if (!err.message[0])
        abort(); /* a failure must say why */
    return 0;
}
