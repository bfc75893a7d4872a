# A firmware run against its committed run (lab/data/*.txt), both as
# "KIND SCENE RENDER 0x… pixels P instr I … stack S" lines, the committed file first:
#   awk -v kind=hash -v scenes="lab far …" -v label="Lab #1" -f .ci/committed-run.awk COMMITTED RUN
# KIND is the lines' first word (`hash` for the renders, `aa` for the anti-aliasing
# firmware's). Every committed render of `scenes` (all scenes where it is empty) must be
# in the run, once, with the same hash, instructions within 1 % and the same stack: the
# docs quote the committed runs' figures, so a render whose stack moved either way fails
# until the run is measured again (the calling script's --update). Exits 1 on any of it.
BEGIN {
    if (kind == "") { print "committed-run.awk: no kind (-v kind=hash)"; bad = 1; exit 1 }
    n = split(scenes, s, " "); for (i = 1; i <= n; i++) pick[s[i]] = 1
}
function field(name,   i) { for (i = 1; i < NF; i++) if ($i == name) return $(i + 1); return "" }
function whole(x) { return x ~ /^[0-9]+$/ }
$1 != kind || (n > 0 && !($2 in pick)) { next }
FNR == NR {
    key = $2 " " $3
    hash[key] = $4; count[key] = field("instr"); stack[key] = field("stack"); committed++
    next
}
{
    key = $2 " " $3
    if (!(key in hash)) { print "not in the committed run: " key; bad++; next }
    if (key in seen) { print "twice in the run: " key; bad++; next }
    seen[key] = 1; compared++
    # As strings: awk would read "0x…" as a (rounded) number.
    if (("" $4) != ("" hash[key])) { print key ": hash " $4 ", committed " hash[key]; bad++ }
    c = field("instr")
    if (!whole(c) || !whole(count[key]) || count[key] == 0) {
        print key ": instructions " c ", committed " count[key]; bad++
    } else {
        change = c / count[key] - 1
        if (change > worst) worst = change
        if (-change > worst) worst = -change
        if (change > 0.01 || change < -0.01) { printf "%s: instructions %+.2f %%\n", key, 100 * change; bad++ }
    }
    b = field("stack")
    if (!whole(b) || !whole(stack[key])) { print key ": stack " b ", committed " stack[key]; bad++ }
    else if (b + 0 != stack[key] + 0) { printf "%s: stack %d B, committed %d B\n", key, b, stack[key]; bad++ }
}
END {
    for (key in hash) if (!(key in seen)) { print "not in the run: " key; bad++ }
    if (bad) exit 1
    printf "%d %s renders: hashes and stacks equal, instructions per pixel within %.3f %% of the committed run\n", compared + 0, label, 100 * worst
}
