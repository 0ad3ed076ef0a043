/* SPDX-License-Identifier: MIT */
/* cl_check.h: every OpenCL call goes through CL_CHECK, which on failure prints the call's text, the
 * error's name, and the host source line, then aborts (OpenCL failures are bugs or broken drivers,
 * not bad input). */
#ifndef PT_CL_CHECK_H
#define PT_CL_CHECK_H

#include <CL/cl.h>

const char *cl_error_name(cl_int code);
_Noreturn void cl_fail(cl_int code, const char *call, const char *file, int line);

#define CL_CHECK(call)                                      \
    do {                                                    \
        cl_int cl_check_status_ = (call);                   \
        if (cl_check_status_ != CL_SUCCESS)                 \
            cl_fail(cl_check_status_, #call, __FILE__, __LINE__); \
    } while (0)

/* For calls that return an object and report through an out-parameter. */
#define CL_CHECK_ERR(status, what)                                 \
    do {                                                           \
        if ((status) != CL_SUCCESS)                                \
            cl_fail((status), (what), __FILE__, __LINE__);         \
    } while (0)

#endif
