# Where a QEMU run's instructions go, from its `-d in_asm,exec,nochain` log: each
# translation block's size is the number of instructions in its `in_asm` listing
# (printed right before the block first runs), each execution is a `Trace` line naming
# the block's pc/flags/cflags and its function. Prints "CLASS INSTRUCTIONS" per class
# of function, then "total INSTRUCTIONS" and "untraced BLOCKS" (executions of blocks
# whose size was never listed; 0 when the log is complete).
#
# Classes, by the function's (mangled) symbol:
#   soft-float   compiler-builtins' float routines and their __aeabi_f*/__aeabi_d*
#                entry points, int<->float conversions, __clzsi2 (their normaliser)
#   int-helpers  compiler-builtins' 64-bit multiply and shifts, integer division, memcpy
#   libm         libm (sqrtf and the rest), fmaxf/fminf
#   kernel       everything else: the kernel, the sink, the firmware
/^IN:/ { listing = 1; first = ""; n = 0; next }
listing && /^0x[0-9a-f]+:/ {
    if (first == "") first = substr($1, 3, length($1) - 3)
    n++
    next
}
listing { if (first != "") { pending = n; pending_pc = first } listing = 0 }
/^Trace/ {
    match($0, /\[[0-9a-f]+\/[0-9a-f]+\/[0-9a-f]+\/[0-9a-f]+\]/)
    split(substr($0, RSTART + 1, RLENGTH - 2), f, "/")
    key = f[2] "/" f[3] "/" f[4]
    if (pending != "" && pending_pc == f[2]) { size[key] = pending; pending = "" }
    if (!(key in size)) { untraced++; next }
    s = $NF
    if (s ~ /compiler_builtins5float/ || s ~ /^__aeabi_[fd]/ || s ~ /^__aeabi_u?i2f$/ || s == "__clzsi2") c = "soft-float"
    else if (s ~ /4libm/ || s == "fmaxf" || s == "fminf") c = "libm"
    else if (s ~ /^__aeabi_l/ || s ~ /divmod|div_rem|memcpy/) c = "int-helpers"
    else c = "kernel"
    count[c] += size[key]
    total += size[key]
}
END {
    for (c in count) print c, count[c]
    print "total", total + 0
    print "untraced", untraced + 0
}
