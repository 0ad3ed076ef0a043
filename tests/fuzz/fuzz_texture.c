// SPDX-License-Identifier: MIT
/* libFuzzer target: the texture loader (stb_image behind the checks of scene/texture.c). */
#include "fuzz_input.h"

#include "scene/texture.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("texture"));
    fuzz_write(path, data, size);
    TextureSet set = {0};
    Error err = {0};
    if (texture_set_add(&set, path, &err) == NO_TEXTURE && !err.message[0])
        abort();
    texture_set_free(&set);
    return 0;
}
