/* robotdesc viewer: draws a robotdesc scene document with plain WebGL 1.0.
 *
 * No dependencies and no network. Each element with a `data-robotdesc-scene` attribute (the
 * id of a JSON script element holding the document written by
 * robotdesc/view/encode.py) becomes a viewer: orbit (drag), pan (shift- or right-drag), zoom
 * (wheel), reset (double-click), select a link (click it, or pick it in the list); toggles for visual and collision geometry, the equivalent
 * inertia boxes and the highlighting of links with findings; a list of links (click one to
 * select it). The page's state is mirrored on the element's data-* attributes for tests.
 */
(function () {
  "use strict";

  var STYLE = [
    ".rd-view{display:flex;font:13px/1.35 system-ui,sans-serif;color:#222;background:#fff;",
    "border:1px solid #ccd;box-sizing:border-box;height:100%;min-height:320px}",
    ".rd-stage{position:relative;flex:1 1 auto;min-width:0}",
    ".rd-stage canvas{width:100%;height:100%;display:block;cursor:grab;background:#f4f5f8}",
    ".rd-hint{position:absolute;left:8px;bottom:6px;color:#667;font-size:11px;",
    "pointer-events:none}",
    ".rd-message{position:absolute;left:12px;top:12px;color:#a11;font-weight:600}",
    ".rd-side{flex:0 0 270px;display:flex;flex-direction:column;border-left:1px solid #ccd;",
    "min-height:0;overflow:hidden}",
    ".rd-title{font-weight:600;padding:8px 10px 2px}",
    ".rd-controls{padding:4px 10px;border-bottom:1px solid #e2e4ea}",
    ".rd-controls label{display:block;white-space:nowrap}",
    ".rd-summary{padding:4px 10px;color:#556}",
    ".rd-filter{margin:2px 10px 6px;padding:2px 4px;font:inherit}",
    ".rd-links{list-style:none;margin:0;padding:0;overflow:auto;flex:1 1 auto;min-height:60px}",
    ".rd-links li{padding:1px 10px;cursor:pointer;white-space:nowrap;overflow:hidden;",
    "text-overflow:ellipsis}",
    ".rd-links li:hover{background:#eef}",
    ".rd-links li.rd-finding{color:#b3261e}",
    ".rd-links li.rd-selected{background:#ffe9a8}",
    ".rd-badge{display:inline-block;min-width:1.4em;margin-left:4px;padding:0 4px;",
    "border-radius:8px;background:#b3261e;color:#fff;font-size:11px;text-align:center}",
    ".rd-detail{border-top:1px solid #e2e4ea;padding:6px 10px;max-height:40%;overflow:auto}",
    ".rd-detail p{margin:2px 0}",
    ".rd-sev-error{color:#b3261e}.rd-sev-warning{color:#9a5b00}.rd-sev-info{color:#33669a}"
  ].join("");

  var VERTEX = [
    "attribute vec3 aPos;attribute vec3 aNormal;",
    "uniform mat4 uProj;uniform mat4 uView;uniform mat4 uModel;",
    "varying vec3 vNormal;",
    "void main(){vNormal=(uView*uModel*vec4(aNormal,0.0)).xyz;",
    "gl_Position=uProj*uView*uModel*vec4(aPos,1.0);}"
  ].join("\n");

  var FRAGMENT = [
    "precision mediump float;",
    "varying vec3 vNormal;uniform vec4 uColor;uniform float uLit;",
    "void main(){vec3 n=normalize(vNormal);",
    "vec3 key=normalize(vec3(0.35,0.55,0.76));vec3 fill=normalize(vec3(-0.6,-0.2,0.5));",
    "float d=0.62*abs(dot(n,key))+0.18*abs(dot(n,fill));",
    "float shade=mix(1.0,0.3+d,uLit);",
    "vec3 lift=vec3(0.14*d*uLit);",  // dark materials still show their form
    "gl_FragColor=vec4(min(uColor.rgb*shade+lift,vec3(1.0)),uColor.a);}"
  ].join("\n");

  var FINDING_COLOR = [0.86, 0.16, 0.12];
  var SELECTED_COLOR = [1.0, 0.78, 0.1];
  var BOX_COLOR = [0.55, 0.3, 0.88, 0.3];
  var BOX_EDGE = [0.35, 0.12, 0.65, 1.0];
  var BAD_BOX_EDGE = [0.9, 0.1, 0.1, 1.0];
  var GRID_COLOR = [0.78, 0.8, 0.85, 1.0];

  // --- small helpers -----------------------------------------------------------------------

  function decode(text, type) {
    var binary = atob(text), bytes = new Uint8Array(binary.length);
    for (var i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
    if (type === "float32") return new Float32Array(bytes.buffer);
    if (type === "uint32") return new Uint32Array(bytes.buffer);
    return new Uint16Array(bytes.buffer);
  }

  function element(tag, cls, text) {
    var node = document.createElement(tag);
    if (cls) node.className = cls;
    if (text !== undefined) node.textContent = text;
    return node;
  }

  function multiply(a, b) {  // column-major 4x4: a * b
    var out = new Array(16);
    for (var c = 0; c < 4; c++) {
      for (var r = 0; r < 4; r++) {
        var s = 0;
        for (var k = 0; k < 4; k++) s += a[k * 4 + r] * b[c * 4 + k];
        out[c * 4 + r] = s;
      }
    }
    return out;
  }

  function perspective(fovy, aspect, near, far) {
    var f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1,
            0, 0, 2 * far * near * nf, 0];
  }

  function lookAt(eye, target, up) {
    var z = normalize(sub(eye, target)), x = normalize(cross(up, z)), y = cross(z, x);
    return [x[0], y[0], z[0], 0, x[1], y[1], z[1], 0, x[2], y[2], z[2], 0,
            -dot(x, eye), -dot(y, eye), -dot(z, eye), 1];
  }

  function scaled(matrix, s) {  // matrix * diag(s, 1)
    var out = matrix.slice();
    for (var c = 0; c < 3; c++) for (var r = 0; r < 4; r++) out[c * 4 + r] *= s[c];
    return out;
  }

  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function cross(a, b) {
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  }
  function normalize(a) {
    var n = Math.sqrt(dot(a, a)) || 1;
    return [a[0] / n, a[1] / n, a[2] / n];
  }
  function mix(a, b, t) {
    return [a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t];
  }

  /** Flat-shaded triangles: positions and per-face normals, three vertices per face. */
  function flatten(positions, indices) {
    var faces = indices.length / 3, pos = new Float32Array(faces * 9);
    var nrm = new Float32Array(faces * 9);
    for (var f = 0; f < faces; f++) {
      var p = [], k;
      for (k = 0; k < 3; k++) {
        var v = indices[f * 3 + k] * 3;
        p.push([positions[v], positions[v + 1], positions[v + 2]]);
        pos[f * 9 + k * 3] = positions[v];
        pos[f * 9 + k * 3 + 1] = positions[v + 1];
        pos[f * 9 + k * 3 + 2] = positions[v + 2];
      }
      var n = normalize(cross(sub(p[1], p[0]), sub(p[2], p[0])));
      for (k = 0; k < 3; k++) {
        nrm[f * 9 + k * 3] = n[0]; nrm[f * 9 + k * 3 + 1] = n[1]; nrm[f * 9 + k * 3 + 2] = n[2];
      }
    }
    return {positions: pos, normals: nrm, count: faces * 3};
  }

  var UNIT_CUBE = (function () {
    var p = [], i, h = 0.5;
    for (i = 0; i < 8; i++) p.push((i & 4 ? h : -h), (i & 2 ? h : -h), (i & 1 ? h : -h));
    var faces = [0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1, 2, 3, 7, 2, 7, 6,
                 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3];
    var edges = [0, 1, 2, 3, 4, 5, 6, 7, 0, 2, 1, 3, 4, 6, 5, 7, 0, 4, 1, 5, 2, 6, 3, 7];
    var lines = [];
    for (i = 0; i < edges.length; i++) lines.push(p[edges[i] * 3], p[edges[i] * 3 + 1],
                                                  p[edges[i] * 3 + 2]);
    return {solid: flatten(new Float32Array(p), faces), lines: new Float32Array(lines)};
  })();

  // --- the viewer ----------------------------------------------------------------------------

  function Viewer(root, doc) {
    this.root = root;
    this.doc = doc;
    root.robotdescViewer = this;
    this.show = {visual: true, collision: false, inertia: false, findings: true};
    var wanted = doc.show || {};
    for (var key in wanted) if (key in this.show) this.show[key] = !!wanted[key];
    this.selected = null;
    this.findings = {};
    for (var i = 0; i < doc.links.length; i++) {
      if (doc.links[i].findings.length) this.findings[doc.links[i].name] = doc.links[i];
    }
    this.buildDom();
    this.gl = null;
    try {
      this.gl = this.canvas.getContext("webgl", {antialias: true, preserveDrawingBuffer: true})
        || this.canvas.getContext("experimental-webgl", {preserveDrawingBuffer: true});
    } catch (error) {
      this.gl = null;
    }
    if (!this.gl) {
      this.stage.appendChild(element("div", "rd-message",
        "WebGL is not available in this browser: the 3D view cannot be drawn."));
      root.setAttribute("data-status", "no-webgl");
      return;
    }
    this.setupGl();
    this.resetCamera();
    this.bindInput();
    this.draw();
    root.setAttribute("data-status", "ready");
  }

  Viewer.prototype.buildDom = function () {
    var self = this, doc = this.doc, root = this.root;
    root.classList.add("rd-view");
    this.stage = element("div", "rd-stage");
    this.canvas = element("canvas");
    this.stage.appendChild(this.canvas);
    this.stage.appendChild(element("div", "rd-hint",
      "click: select a link \u00b7 drag: rotate \u00b7 shift/right-drag: pan \u00b7 wheel: zoom " +
      "\u00b7 double-click: reset"));
    root.appendChild(this.stage);
    var side = element("div", "rd-side");
    side.appendChild(element("div", "rd-title", doc.title || doc.robot));
    var controls = element("div", "rd-controls");
    var names = {visual: "visual geometry", collision: "collision geometry",
                 inertia: "inertia boxes (equivalent)", findings: "highlight links with findings"};
    Object.keys(names).forEach(function (key) {
      var label = element("label"), box = element("input");
      box.type = "checkbox";
      box.checked = self.show[key];
      box.setAttribute("data-toggle", key);
      box.addEventListener("change", function () {
        self.show[key] = box.checked;
        self.redraw();
      });
      label.appendChild(box);
      label.appendChild(document.createTextNode(" " + names[key]));
      controls.appendChild(label);
    });
    side.appendChild(controls);
    var withFindings = Object.keys(this.findings).length;
    var summary = doc.links.length + " links, " + withFindings + " with findings";
    if (doc.problems.length) summary += ", " + doc.problems.length + " geometries not shown";
    side.appendChild(element("div", "rd-summary", summary));
    var filter = element("input", "rd-filter");
    filter.type = "search";
    filter.placeholder = "filter links";
    filter.addEventListener("input", function () {
      var text = filter.value.toLowerCase();
      Object.keys(self.items).forEach(function (name) {
        self.items[name].style.display = name.toLowerCase().indexOf(text) >= 0 ? "" : "none";
      });
    });
    side.appendChild(filter);
    this.list = element("ul", "rd-links");
    this.items = {};
    doc.links.forEach(function (link) {
      var item = element("li", link.findings.length ? "rd-finding" : "", link.name);
      item.setAttribute("data-link", link.name);
      item.title = link.name;
      if (link.findings.length) item.appendChild(element("span", "rd-badge",
                                                         String(link.findings.length)));
      item.addEventListener("click", function () {
        self.select(self.selected === link.name ? null : link.name);
      });
      self.items[link.name] = item;
      self.list.appendChild(item);
    });
    side.appendChild(this.list);
    this.detail = element("div", "rd-detail");
    side.appendChild(this.detail);
    root.appendChild(side);
    this.showDetail();
  };

  Viewer.prototype.select = function (name) {
    if (this.selected && this.items[this.selected]) {
      this.items[this.selected].classList.remove("rd-selected");
    }
    this.selected = name;
    if (name && this.items[name]) {
      this.items[name].classList.add("rd-selected");
      if (this.items[name].scrollIntoView) this.items[name].scrollIntoView({block: "nearest"});
    }
    this.root.setAttribute("data-selected", name || "");
    this.showDetail();
    this.redraw();
  };

  Viewer.prototype.showDetail = function () {
    var detail = this.detail, doc = this.doc, name = this.selected;
    detail.textContent = "";
    if (!name) {
      var lines = doc.problems.slice(0, 20).map(function (p) {
        return p.link + " " + p.kind + "[" + p.index + "]: " + p.message;
      });
      detail.appendChild(element("p", "", lines.length ? "Not shown:" :
                                 "Click a link to see its findings."));
      lines.forEach(function (text) { detail.appendChild(element("p", "", text)); });
      return;
    }
    var link = null, box = null, i;
    for (i = 0; i < doc.links.length; i++) if (doc.links[i].name === name) link = doc.links[i];
    for (i = 0; i < doc.inertia_boxes.length; i++) {
      if (doc.inertia_boxes[i].link === name) box = doc.inertia_boxes[i];
    }
    detail.appendChild(element("p", "", name));
    detail.appendChild(element("p", "", "faces: " + link.visual_faces + " visual, " +
                               link.collision_faces + " collision"));
    if (box) {
      detail.appendChild(element("p", "", "mass " + box.mass.toPrecision(4) + " kg; box " +
        box.size.map(function (v) { return (1000 * v).toFixed(1); }).join(" \u00d7 ") + " mm" +
        (box.valid ? "" : " (moments violate the triangle inequality)")));
    }
    link.findings.forEach(function (f) {
      detail.appendChild(element("p", "rd-sev-" + f.severity,
                                 f.code + " " + f.severity + ": " + f.message));
    });
  };

  Viewer.prototype.setupGl = function () {
    var gl = this.gl;
    function compile(type, source) {
      var shader = gl.createShader(type);
      gl.shaderSource(shader, source);
      gl.compileShader(shader);
      if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
        throw new Error("shader: " + gl.getShaderInfoLog(shader));
      }
      return shader;
    }
    var program = gl.createProgram();
    gl.attachShader(program, compile(gl.VERTEX_SHADER, VERTEX));
    gl.attachShader(program, compile(gl.FRAGMENT_SHADER, FRAGMENT));
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
      throw new Error("program: " + gl.getProgramInfoLog(program));
    }
    gl.useProgram(program);
    this.loc = {
      pos: gl.getAttribLocation(program, "aPos"), normal: gl.getAttribLocation(program, "aNormal"),
      proj: gl.getUniformLocation(program, "uProj"), view: gl.getUniformLocation(program, "uView"),
      model: gl.getUniformLocation(program, "uModel"),
      color: gl.getUniformLocation(program, "uColor"), lit: gl.getUniformLocation(program, "uLit")
    };
    var self = this;
    function upload(data) {
      var buffer = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
      gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
      return buffer;
    }
    function mesh(flat) {
      return {pos: upload(flat.positions), normal: upload(flat.normals), count: flat.count};
    }
    this.meshes = this.doc.geometries.map(function (g) {
      return mesh(flatten(decode(g.positions, "float32"), decode(g.indices, g.index_type)));
    });
    this.cube = mesh(UNIT_CUBE.solid);
    this.cubeLines = {pos: upload(UNIT_CUBE.lines), count: UNIT_CUBE.lines.length / 3};
    this.grid = this.makeGrid(upload);
    self.triangles = 0;
  };

  Viewer.prototype.makeGrid = function (upload) {
    var b = this.doc.bounds, lines = [];
    var size = Math.max(b[1][0] - b[0][0], b[1][1] - b[0][1], 0.1) * 1.5;
    var step = Math.pow(10, Math.floor(Math.log(size / 4) / Math.LN10));
    var cx = (b[0][0] + b[1][0]) / 2, cy = (b[0][1] + b[1][1]) / 2, z = b[0][2];
    var half = Math.ceil(size / 2 / step) * step;
    cx = Math.round(cx / step) * step;
    cy = Math.round(cy / step) * step;
    for (var t = -half; t <= half + 1e-9; t += step) {
      lines.push(cx + t, cy - half, z, cx + t, cy + half, z, cx - half, cy + t, z,
                 cx + half, cy + t, z);
    }
    return {pos: upload(new Float32Array(lines)), count: lines.length / 3};
  };

  Viewer.prototype.resetCamera = function () {
    var b = this.doc.bounds;
    this.target = [(b[0][0] + b[1][0]) / 2, (b[0][1] + b[1][1]) / 2, (b[0][2] + b[1][2]) / 2];
    var radius = Math.max(0.5 * Math.sqrt(dot(sub(b[1], b[0]), sub(b[1], b[0]))), 0.05);
    this.fovy = 40 * Math.PI / 180;
    this.distance = 1.15 * radius / Math.sin(this.fovy / 2);
    this.azimuth = -50 * Math.PI / 180;
    this.elevation = 25 * Math.PI / 180;
  };

  Viewer.prototype.eye = function () {
    var ce = Math.cos(this.elevation);
    return [this.target[0] + this.distance * ce * Math.cos(this.azimuth),
            this.target[1] + this.distance * ce * Math.sin(this.azimuth),
            this.target[2] + this.distance * Math.sin(this.elevation)];
  };

  Viewer.prototype.bindInput = function () {
    var self = this, canvas = this.canvas, last = null, mode = null;
    canvas.addEventListener("contextmenu", function (event) { event.preventDefault(); });
    var pressed = null;
    canvas.addEventListener("mousedown", function (event) {
      mode = (event.button === 2 || event.shiftKey) ? "pan" : "orbit";
      last = [event.clientX, event.clientY];
      pressed = last;
      event.preventDefault();
    });
    window.addEventListener("mouseup", function (event) {
      mode = null;
      if (pressed && event.target === canvas && event.button === 0 &&
          Math.abs(event.clientX - pressed[0]) + Math.abs(event.clientY - pressed[1]) < 4) {
        var box = canvas.getBoundingClientRect();
        var link = self.pick(event.clientX - box.left, event.clientY - box.top);
        self.select(link === self.selected ? null : link);
      }
      pressed = null;
    });
    window.addEventListener("mousemove", function (event) {
      if (!mode) return;
      var dx = event.clientX - last[0], dy = event.clientY - last[1];
      last = [event.clientX, event.clientY];
      self.move(mode, dx, dy);
    });
    canvas.addEventListener("wheel", function (event) {
      event.preventDefault();
      self.distance *= Math.exp(Math.max(-100, Math.min(100, event.deltaY)) * 0.002);
      self.redraw();
    }, {passive: false});
    canvas.addEventListener("dblclick", function () { self.resetCamera(); self.redraw(); });
    canvas.addEventListener("touchstart", function (event) {
      if (event.touches.length === 1) last = [event.touches[0].clientX, event.touches[0].clientY];
    });
    canvas.addEventListener("touchmove", function (event) {
      if (event.touches.length !== 1 || !last) return;
      event.preventDefault();
      var t = event.touches[0];
      self.move("orbit", t.clientX - last[0], t.clientY - last[1]);
      last = [t.clientX, t.clientY];
    }, {passive: false});
    window.addEventListener("resize", function () { self.redraw(); });
  };

  Viewer.prototype.move = function (mode, dx, dy) {
    if (mode === "orbit") {
      this.azimuth -= dx * 0.008;
      this.elevation = Math.max(-1.55, Math.min(1.55, this.elevation + dy * 0.008));
    } else {
      var eye = this.eye(), forward = normalize(sub(this.target, eye));
      var right = normalize(cross(forward, [0, 0, 1])), up = cross(right, forward);
      var scale = this.distance * 0.0015;
      for (var i = 0; i < 3; i++) this.target[i] += (-dx * right[i] + dy * up[i]) * scale;
    }
    this.redraw();
  };

  /** The link drawn at canvas position (x, y) in CSS pixels, or null: each visible shape is
   *  drawn in a colour that encodes its index into an offscreen buffer, and one pixel read. */
  Viewer.prototype.pick = function (x, y) {
    var gl = this.gl, self = this, width = this.canvas.width, height = this.canvas.height;
    if (!gl) return null;
    var target = this.pickTarget;
    if (!target || target.width !== width || target.height !== height) {
      target = {width: width, height: height, frame: gl.createFramebuffer(),
                color: gl.createTexture(), depth: gl.createRenderbuffer()};
      gl.bindTexture(gl.TEXTURE_2D, target.color);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, width, height, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.bindRenderbuffer(gl.RENDERBUFFER, target.depth);
      gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT16, width, height);
      gl.bindFramebuffer(gl.FRAMEBUFFER, target.frame);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target.color, 0);
      gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER,
                                 target.depth);
      this.pickTarget = target;
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.frame);
    gl.viewport(0, 0, width, height);
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.disable(gl.BLEND);
    gl.depthMask(true);
    this.doc.instances.forEach(function (instance, index) {
      if (!(instance.kind === "visual" ? self.show.visual : self.show.collision)) return;
      var id = index + 1;
      self.drawMesh(self.meshes[instance.geometry], instance.matrix,
                    [(id & 255) / 255, ((id >> 8) & 255) / 255, ((id >> 16) & 255) / 255, 1],
                    0, gl.TRIANGLES);
    });
    var ratio = width / Math.max(1, this.canvas.clientWidth), pixel = new Uint8Array(4);
    gl.readPixels(Math.floor(x * ratio), height - 1 - Math.floor(y * ratio), 1, 1, gl.RGBA,
                  gl.UNSIGNED_BYTE, pixel);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.enable(gl.BLEND);
    var hit = pixel[0] + pixel[1] * 256 + pixel[2] * 65536;
    return hit > 0 && hit <= this.doc.instances.length ? this.doc.instances[hit - 1].link : null;
  };

  Viewer.prototype.redraw = function () {
    var self = this;
    if (!this.gl || this.pending) return;
    this.pending = true;
    (window.requestAnimationFrame || setTimeout)(function () {
      self.pending = false;
      self.draw();
    });
  };

  Viewer.prototype.color = function (instance) {
    var rgb = instance.color.slice(0, 3), alpha = instance.color[3];
    if (this.show.findings && this.findings[instance.link]) rgb = mix(rgb, FINDING_COLOR, 0.75);
    if (this.selected === instance.link) rgb = mix(rgb, SELECTED_COLOR, 0.8);
    return [rgb[0], rgb[1], rgb[2], alpha];
  };

  Viewer.prototype.drawMesh = function (mesh, model, color, lit, mode) {
    var gl = this.gl, loc = this.loc;
    gl.uniformMatrix4fv(loc.model, false, new Float32Array(model));
    gl.uniform4fv(loc.color, color);
    gl.uniform1f(loc.lit, lit);
    gl.bindBuffer(gl.ARRAY_BUFFER, mesh.pos);
    gl.vertexAttribPointer(loc.pos, 3, gl.FLOAT, false, 0, 0);
    if (mesh.normal) {
      gl.enableVertexAttribArray(loc.normal);
      gl.bindBuffer(gl.ARRAY_BUFFER, mesh.normal);
      gl.vertexAttribPointer(loc.normal, 3, gl.FLOAT, false, 0, 0);
    } else {
      gl.disableVertexAttribArray(loc.normal);
      gl.vertexAttrib3f(loc.normal, 0, 0, 1);
    }
    gl.drawArrays(mode, 0, mesh.count);
    if (mode === gl.TRIANGLES) this.triangles += mesh.count / 3;
  };

  Viewer.prototype.draw = function () {
    var gl = this.gl, doc = this.doc, show = this.show, self = this;
    var ratio = window.devicePixelRatio || 1;
    var width = Math.max(1, Math.round(this.canvas.clientWidth * ratio));
    var height = Math.max(1, Math.round(this.canvas.clientHeight * ratio));
    if (this.canvas.width !== width || this.canvas.height !== height) {
      this.canvas.width = width;
      this.canvas.height = height;
    }
    gl.viewport(0, 0, width, height);
    gl.clearColor(0.957, 0.961, 0.973, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.enableVertexAttribArray(this.loc.pos);
    var near = this.distance * 0.01, far = this.distance * 20;
    gl.uniformMatrix4fv(this.loc.proj, false,
                        new Float32Array(perspective(this.fovy, width / height, near, far)));
    gl.uniformMatrix4fv(this.loc.view, false,
                        new Float32Array(lookAt(this.eye(), this.target, [0, 0, 1])));
    var identity = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    this.triangles = 0;
    gl.depthMask(true);
    this.drawMesh(this.grid, identity, GRID_COLOR, 0, gl.LINES);

    var translucent = [];
    doc.instances.forEach(function (instance) {
      var visible = instance.kind === "visual" ? show.visual : show.collision;
      if (!visible) return;
      var color = self.color(instance);
      if (instance.kind === "collision" && !show.visual) color[3] = 1.0;
      if (color[3] < 0.99) {
        translucent.push([instance, color]);
      } else {
        self.drawMesh(self.meshes[instance.geometry], instance.matrix, color, 1, gl.TRIANGLES);
      }
    });
    gl.depthMask(false);
    translucent.forEach(function (item) {
      self.drawMesh(self.meshes[item[0].geometry], item[0].matrix, item[1], 1, gl.TRIANGLES);
    });
    if (show.inertia) {
      doc.inertia_boxes.forEach(function (box) {
        var model = scaled(box.matrix, box.size.map(function (v) { return Math.max(v, 1e-5); }));
        var fill = BOX_COLOR;
        if (self.selected === box.link) fill = [1.0, 0.78, 0.1, 0.45];
        self.drawMesh(self.cube, model, fill, 1, gl.TRIANGLES);
        self.drawMesh(self.cubeLines, model, box.valid ? BOX_EDGE : BAD_BOX_EDGE, 0, gl.LINES);
      });
    }
    gl.depthMask(true);
    this.root.setAttribute("data-triangles", String(this.triangles));
  };

  function mountAll() {
    var roots = document.querySelectorAll("[data-robotdesc-scene]");
    for (var i = 0; i < roots.length; i++) {
      var root = roots[i];
      if (root.getAttribute("data-status")) continue;
      try {
        var source = document.getElementById(root.getAttribute("data-robotdesc-scene"));
        new Viewer(root, JSON.parse(source.textContent));
      } catch (error) {
        root.setAttribute("data-status", "error");
        root.appendChild(element("div", "rd-message", "robotdesc viewer: " + error.message));
      }
    }
  }

  if (!document.getElementById("robotdesc-viewer-style")) {
    var style = element("style");
    style.id = "robotdesc-viewer-style";
    style.textContent = STYLE;
    document.head.appendChild(style);
  }
  window.RobotdescViewer = {mount: function (root, doc) { return new Viewer(root, doc); },
                            mountAll: mountAll};
  mountAll();
})();
