/* SPDX-License-Identifier: MIT */
/* test_group_exclusive_sum: runs cl/parallel/scan.cl's work-group scan on in[], one value per work item;
 * writes each item's exclusive prefix to prefix[] and each group's total to totals[group].
 * scratch: 2 uints per work item. */
kernel void test_group_exclusive_sum(global const uint *in, global uint *prefix,
                                     global uint *totals, local uint *scratch)
{
    uint total;
    prefix[get_global_id(0)] = group_exclusive_sum(in[get_global_id(0)], scratch, &total);
    if (get_local_id(0) == 0)
        totals[get_group_id(0)] = total;
}
