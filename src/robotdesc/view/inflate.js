/* Raw DEFLATE (RFC 1951) decoder for the notebook preview of robotdesc views: the page arrives
 * compressed and is unpacked synchronously, in any browser, also in a sandboxed frame. */
function rdInflate(src) {
  var out = [], pos = 0, bit = 0, i;
  function bits(n) {
    var v = 0;
    for (var k = 0; k < n; k++) {
      v |= ((src[pos] >> bit) & 1) << k;
      if (++bit === 8) { bit = 0; pos++; }
    }
    return v;
  }
  function build(lens) {
    var count = [], offs = [], sym = [], n;
    for (n = 0; n < 16; n++) count[n] = 0;
    for (n = 0; n < lens.length; n++) count[lens[n]]++;
    count[0] = 0; offs[1] = 0;
    for (n = 1; n < 15; n++) offs[n + 1] = offs[n] + count[n];
    for (n = 0; n < lens.length; n++) if (lens[n]) sym[offs[lens[n]]++] = n;
    return {count: count, sym: sym};
  }
  function decode(h) {
    var code = 0, first = 0, index = 0;
    for (var len = 1; len < 16; len++) {
      code |= bits(1);
      var c = h.count[len];
      if (code - c < first) return h.sym[index + (code - first)];
      index += c; first += c; first <<= 1; code <<= 1;
    }
    throw new Error("bad deflate data");
  }
  var LB = [3,4,5,6,7,8,9,10,11,13,15,17,19,23,27,31,35,43,51,59,67,83,99,115,131,163,195,227,258],
      LE = [0,0,0,0,0,0,0,0,1,1,1,1,2,2,2,2,3,3,3,3,4,4,4,4,5,5,5,5,0],
      DB = [1,2,3,4,5,7,9,13,17,25,33,49,65,97,129,193,257,385,513,769,1025,1537,2049,3073,
            4097,6145,8193,12289,16385,24577],
      DE = [0,0,0,0,1,1,2,2,3,3,4,4,5,5,6,6,7,7,8,8,9,9,10,10,11,11,12,12,13,13],
      ORDER = [16,17,18,0,8,7,9,6,10,5,11,4,12,3,13,2,14,1,15], last;
  do {
    last = bits(1);
    var type = bits(2), lit, dist;
    if (type === 0) {
      if (bit) { bit = 0; pos++; }
      var stored = src[pos] | (src[pos + 1] << 8);
      pos += 4;
      for (i = 0; i < stored; i++) out.push(src[pos++]);
      continue;
    }
    if (type === 1) {
      var fixed = [], fd = [];
      for (i = 0; i < 288; i++) fixed[i] = i < 144 ? 8 : i < 256 ? 9 : i < 280 ? 7 : 8;
      for (i = 0; i < 30; i++) fd[i] = 5;
      lit = build(fixed); dist = build(fd);
    } else {
      var nlen = bits(5) + 257, ndist = bits(5) + 1, ncode = bits(4) + 4, cl = [], lens = [];
      for (i = 0; i < 19; i++) cl[i] = 0;
      for (i = 0; i < ncode; i++) cl[ORDER[i]] = bits(3);
      var ch = build(cl);
      while (lens.length < nlen + ndist) {
        var s = decode(ch);
        if (s < 16) { lens.push(s); continue; }
        var value = 0, repeat;
        if (s === 16) { value = lens[lens.length - 1]; repeat = 3 + bits(2); }
        else if (s === 17) repeat = 3 + bits(3);
        else repeat = 11 + bits(7);
        while (repeat--) lens.push(value);
      }
      lit = build(lens.slice(0, nlen)); dist = build(lens.slice(nlen));
    }
    for (;;) {
      var sym = decode(lit);
      if (sym < 256) { out.push(sym); continue; }
      if (sym === 256) break;
      sym -= 257;
      var length = LB[sym] + bits(LE[sym]), d = decode(dist);
      var start = out.length - (DB[d] + bits(DE[d]));
      for (i = 0; i < length; i++) out.push(out[start + i]);
    }
  } while (!last);
  return new Uint8Array(out);
}
