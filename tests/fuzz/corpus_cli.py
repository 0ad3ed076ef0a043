# SPDX-License-Identifier: MIT
"""Cases for outputs, the command line and the environment (layout variables, the kernel cache).
"""
from corpus_cases import TINY, TRIANGLE, case


def cli_cases():
    scene = {"tri.obj": TRIANGLE}
    base = ["render", "tri.obj", "--width", "8", "--height", "8", "--spp", "1", "--max-depth", "2",
            "--device", "cpu", "--quiet"]
    for name, out, setup, expect in [
            ("png", "o.png", None, "ok"), ("exr", "o.exr", None, "ok"), ("upper", "O.PNG", None, "ok"),
            ("tiff", "o.tiff", None, "error"), ("no-extension", "o", None, "error"),
            ("empty", "", None, "error"), ("dot-png", ".png", None, "ok"),
            ("directory", "d.png", "mkdir d.png", "error"),
            ("missing-folder", "no/such/dir/o.png", None, "error"),
            ("proc", "/proc/o.png", None, "error"),
            ("read-only-file", "ro.png", "touch ro.png && chattr +i ro.png 2>/dev/null || true", "any"),
            ("long-name", "n" * 300 + ".png", None, "error"),
            ("long-path", "/".join(["d" * 200] * 8) + "/o.png", None, "error")]:
        case("out-" + name, scene, base + ["-o", out], expect, setup=setup)
    case("out-dev-full", scene, base + ["-o", "full.png"], "error", setup="ln -s /dev/full full.png")
    case("out-preview-exr", scene, base + ["-o", "o.exr", "--preview"], "ok")
    case("out-default-folder-is-file", scene, base, "error", setup="touch out")
    case("out-aov-albedo", scene, base + ["-o", "a.png", "--aov", "albedo"], "error")  # a PNG holds no layers
    case("out-aov-depth-exr", scene, base + ["-o", "a.exr", "--aov", "depth"], "ok")

    opts = {"--spp": ["0", "-1", "abc", "1.5", "", "99999999999", "0x10", "1e3", " 1"],
            "--max-depth": ["0", "1025", "-3", "x", ""], "--width": ["0", "65537", "-8", "w", "1e9"],
            "--height": ["0", "65537", "h"], "--seed": ["-1", "abc", "99999999999999999999", "1.5"],
            "--exposure": ["nan", "inf", "-inf", "1e308", "x", ""],
            "--aov": ["shiny", "", "ALBEDO"], "--device": ["gpu", "9:9", "-1:0", "0:", ":0", "abc",
                                                            "0:0:0", "99999999999:0", ""],
            "--camera": ["{", "[]", '{"eye": "x"}', '{"fov_y": -1}', '{"bogus": 1}', "null", ""],
            "--frames": ["0", "-1", "x"], "--csv": ["", "/proc/x.csv"],
            "--denoise-device": ["tpu", "", "GPU", "cpu,gpu"]}
    for opt, values in opts.items():
        for i, value in enumerate(values):
            args = [a for a in base]
            if opt in args:
                at = args.index(opt)
                args[at + 1] = value
            else:
                args += [opt, value]
            case("arg%s-%d" % (opt, i), scene, args + ["-o", "o.png"], "any")
        case("arg%s-missing-value" % opt, scene, ["render", "tri.obj", opt], "error")
    for name, args in [("none", []), ("unknown-command", ["frobnicate"]), ("help", ["help"]),
                       ("dash-h", ["-h"]), ("render-no-scene", ["render"]),
                       ("unknown-option", base + ["--bogus"]), ("two-scenes", base + ["tri.obj"]),
                       ("option-first", ["--spp", "1", "render", "tri.obj"]),
                       ("devices-extra", ["devices", "extra"]), ("devices", ["devices"]),
                       ("long-arg", ["render", "x" * 100000]),
                       ("non-utf8", ["render", "\udcff\udcfe.obj"]),
                       ("empty-scene-arg", ["render", ""]), ("repeated-spp", base + ["--spp", "1"]),
                       ("view-no-display", ["view", "tri.obj", "--device", "cpu", "--frames", "1"]),
                       ("bench-bad-csv", ["bench", "tri.obj", "--device", "cpu", "--spp", "1",
                                          "--width", "8", "--height", "8", "--csv", "/proc/x"])]:
        env = {"DISPLAY": None, "WAYLAND_DISPLAY": None} if name == "view-no-display" else None
        case("cli-" + name, scene, args, "any", env=env)


def env_cases():
    scene = {"tri.obj": TRIANGLE}
    base = ["render", "tri.obj"] + TINY
    # Valid non-default layouts are left out: each would compile the kernels once more.
    settings = [("PT_BVH_WIDTH", ["0", "1", "3", "16", "abc", "", "-2", "8", "2x"]),
                ("PT_BVH_QUANTIZED", ["2", "x", "", "0", "1"]),
                ("PT_EXACT_MATHS", ["2", "x", "", "0", "1"]),
                ("PT_NO_CACHE", ["1", "0", "yes", ""]),
                ("PT_KERNEL_CACHE_MB", ["0", "-1", "abc", "1", "", "99999999999"]),
                ("PT_CACHE_BINARIES", ["2", "x", ""]),
                ("PT_PROGRAM_PARTS", ["2", "x", ""]),
                ("PT_MEGAKERNEL", ["0", "1", "2", "on", ""]),
                ("PT_PACKETS", ["0", "1", "2", "off", ""]),
                ("PT_LOCAL_SIZE", ["0", "-1", "abc", "1", "3", "100000", "99999999999"]),
                ("PT_WINDOW_POOLS", ["0", "-1", "abc", "1", "4097", "99999999999", ""]),
                ("PT_POOL_SIZE", ["0", "-1", "abc", "1023", "1024", "268435457", "99999999999", ""]),
                ("PT_CL_OPTIONS", ["-this-is-not-an-option", "-D"]),
                ("OCL_ICD_VENDORS", ["/nonexistent"])]
    for var, values in settings:
        for i, value in enumerate(values):
            case("env-%s-%d" % (var, i), scene, base, "any", env={var: value})
    # The wavefront's tail (read where the wavefront renders: PT_MEGAKERNEL=0 on a CPU).
    for i, value in enumerate(["-1", "abc", "0", "1", "99999999999", "", "2x"]):
        case("env-PT_TAIL_PATHS-%d" % i, scene, base, "any",
             env={"PT_TAIL_PATHS": value, "PT_MEGAKERNEL": "0"})
    # Issue 42: PT_TEST_RAISE with bad values is one line; good ones stop the render (unit path
    # and --quiet included) and still write the image.
    for i, value in enumerate(["SEGV@render", "INT@", "@render", "TERM@unit:0", "TERM@unit:x",
                               "HUP@nowhere", "INT@render:99999999999", "", "TERM"]):
        case("env-PT_TEST_RAISE-bad-%d" % i, scene, base, "any", env={"PT_TEST_RAISE": value})
    for i, (value, extra) in enumerate([("TERM@render", []), ("INT@unit", ["--unit-spp", "1"]),
                                        ("HUP@unit", ["--checkpoint", "1000"])]):
        case("env-PT_TEST_RAISE-stop-%d" % i, scene, base + extra, "any",
             env={"PT_TEST_RAISE": value})
    # Flags given a value, the confinement option, time limits on the unit path.
    for i, args in enumerate([["--help=1"], ["render", "--help=1"], base + ["--quiet=2"],
                              base + ["--allow-outside-paths=1"], base + ["--allow-outside-paths"],
                              base + ["--unit-spp", "1", "--time-limit", "0.001"],
                              base + ["--checkpoint", "1000", "--time-limit", "0.001"]]):
        case("cli-issue42-%d" % i, scene, args, "any")
    # An MTL texture path that leaves the folder: refused unless --allow-outside-paths.
    mtl_scene = {"m.obj": "mtllib m.mtl\n" + TRIANGLE.replace("f 1", "usemtl a\nf 1"),
                 "m.mtl": "newmtl a\nmap_Kd ../../../../etc/passwd\n"}
    case("mtl-escape", mtl_scene, ["render", "m.obj"] + TINY, "error", needle="leaves the file")
    case("mtl-escape-allowed", mtl_scene, ["render", "m.obj", "--allow-outside-paths"] + TINY, "any")
    cache_env = {"XDG_CACHE_HOME": "cache"}
    for name, xdg, setup in [("file", "f", "touch f"), ("proc", "/proc/cache", None),
                             ("missing-deep", "a/b/c/d", None), ("long", "l" * 3000, None),
                             ("relative-dot", ".", None), ("empty", "", None)]:
        case("env-cache-home-" + name, scene, base, "ok", env={"XDG_CACHE_HOME": xdg}, setup=setup)
    case("env-no-home", scene, base, "ok", env={"XDG_CACHE_HOME": None, "HOME": None})
    # Without POCL_CACHE_DIR, PoCL's cache is in the unusable cache home too (it offered no device).
    case("env-cache-home-file-pocl", scene, base, "ok",
         env={"XDG_CACHE_HOME": "f", "POCL_CACHE_DIR": None}, setup="touch f")
    # A warm cache copied in, then damaged: truncated at several sizes, zeroed, replaced.
    copy = 'mkdir -p cache && cp -r "$PT_FUZZ_CACHE/pt" cache/ && for f in cache/pt/*.bin; do '
    for name, damage in [("empty", ': > "$f"'), ("1-byte", 'truncate -s 1 "$f"'),
                         ("31-bytes", 'truncate -s 31 "$f"'), ("32-bytes", 'truncate -s 32 "$f"'),
                         ("1000-bytes", 'truncate -s 1000 "$f"'),
                         ("half", 'truncate -s $(( $(stat -c %s "$f") / 2 )) "$f"'),
                         ("minus-1", 'truncate -s -1 "$f"'), ("plus-zeros", 'truncate -s +4096 "$f"'),
                         ("flipped", 'printf x | dd of="$f" bs=1 seek=5000 conv=notrunc 2>/dev/null'),
                         ("garbage", 'head -c 100000 /dev/urandom > "$f"'),
                         ("directory", 'rm "$f" && mkdir "$f"'), ("fifo", 'rm "$f" && mkfifo "$f"'),
                         ("dev-zero", 'rm "$f" && ln -s /dev/zero "$f"'),
                         ("read-only-folder", 'chmod 555 cache/pt')]:
        case("cache-" + name, scene, base, "ok", env=cache_env, setup=copy + damage + "; done")
        # The same damage to a program binary (the warm cache has one: replay.py's second warm-up;
        # on PoCL pt stores binaries only when asked to, kernel_cache.h).
        if name in ("empty", "32-bytes", "half", "flipped", "garbage"):
            case("cache-binary-" + name, scene, base, "ok",
                 env=dict(cache_env, PT_CACHE_BINARIES="1"), setup=copy + damage + "; done")
