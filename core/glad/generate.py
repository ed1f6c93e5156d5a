#!/usr/bin/env python3
"""Generates the GL 4.5 core loader with Debian's glad (python3-glad) at build time.

Meson custom targets cannot write into subfolders, so glad runs in a temporary
folder and its three files are copied flat into this target's folder, with the
two includes between them made relative. Code includes <glad/gl.h> as usual.
Usage: generate.py OUT_GL_C OUT_GL_H OUT_KHRPLATFORM_H
"""
import os
import shutil
import subprocess
import sys
import tempfile

def main():
    out_c, out_h, out_khr = sys.argv[1:4]
    with tempfile.TemporaryDirectory() as tmp:
        # --reproducible: without it glad fetches the newest XML spec over the network.
        cmd = [sys.executable, "-m", "glad", "--reproducible", "--quiet",
               "--api", "gl:core=4.5", "--extensions", "GL_KHR_debug",
               "--out-path", tmp, "c", "--loader"]
        subprocess.run(cmd, check=True)
        with open(os.path.join(tmp, "src", "gl.c")) as f:
            src = f.read().replace("#include <glad/gl.h>", '#include "gl.h"')
        with open(os.path.join(tmp, "include", "glad", "gl.h")) as f:
            hdr = f.read().replace("#include <KHR/khrplatform.h>", '#include "khrplatform.h"')
        with open(out_c, "w") as f:
            f.write(src)
        with open(out_h, "w") as f:
            f.write(hdr)
        shutil.copyfile(os.path.join(tmp, "include", "KHR", "khrplatform.h"), out_khr)

if __name__ == "__main__":
    main()
