// SPDX-License-Identifier: MIT
/* libFuzzer target: the Mitsuba 3 XML importer (host/io/xml_tree.c, host/scene/import_mitsuba.c
 * and mitsuba_*.c) and the JSON scene reader behind it (scene_desc_load of an .xml file). The
 * input is the XML file; a small OBJ and an included file lie beside it for the references a
 * mutated scene may keep. */
#include "fuzz_input.h"

#include "scene/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static bool beside;
    if (!beside) {
        static const char triangle[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n";
        static const char part[] = "<scene version=\"3.0.0\"><bsdf type=\"diffuse\" id=\"inc\"/></scene>";
        fuzz_write(fuzz_path("tri.obj"), (const uint8_t *)triangle, sizeof triangle - 1);
        fuzz_write(fuzz_path("part.xml"), (const uint8_t *)part, sizeof part - 1);
        beside = true;
    }
    char path[128];
    snprintf(path, sizeof path, "%s", fuzz_path("scene.xml"));
    fuzz_write(path, data, size);
    SceneDesc desc;
    Error err = {0};
    if (scene_desc_load(path, &desc, &err))
        scene_desc_free(&desc);
    else if (!err.message[0])
        abort(); /* a failure must say why */
    return 0;
}
