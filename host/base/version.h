/* SPDX-License-Identifier: MIT */
/* version.h: pt's version, as `pt --version` prints it and the EXR header records it. */
#ifndef PT_VERSION_H
#define PT_VERSION_H

#define PT_VERSION "2.0.0-dev"

#endif
