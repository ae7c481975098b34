// Renders a .glb, or the ShaderMaterial of an ES module written by `brdfit export --format
// threejs` (a .mjs whose default export makes the material) on a 128 x 64 band sphere, with three.js (pinned in package-lock.json) in headless Chromium (software
// WebGL 2, SwiftShader) and writes the canvas as an 8-bit sRGB PNG. The scene matches a brdfit
// scene file with those values (docs/scenes.md): perspective camera at (0, 0, 4) looking at
// the origin, 30 degree vertical field of view; one directional light towards DIR with
// irradiance INTENSITY at normal incidence (three.js's physical lights, brdfit's
// "punctual_pi": false); black background; no tone mapping; sRGB output.
// Usage: node render_three.cjs GLB|MJS OUT.png SIZE DIR_X,DIR_Y,DIR_Z INTENSITY
'use strict';
const fs = require('fs');
const http = require('http');
const path = require('path');
const { execFile } = require('child_process');

const [glb, out, size, dir, intensity] = process.argv.slice(2);
if (!intensity) {
  console.error('usage: node render_three.cjs GLB OUT.png SIZE X,Y,Z INTENSITY');
  process.exit(2);
}
const three = path.join(__dirname, 'node_modules', 'three');
const isModule = glb.endsWith('.mjs');

const page = `<!DOCTYPE html><html><head><script type="importmap">
{"imports": {"three": "/three/build/three.module.js", "three/addons/": "/three/examples/jsm/"}}
</script></head><body style="margin:0"><pre id="out">pending</pre><script type="module">
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
const out = document.getElementById('out');
try {
  const size = ${Number(size)};
  const renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setSize(size, size);
  renderer.outputColorSpace = THREE.SRGBColorSpace;
  renderer.toneMapping = THREE.NoToneMapping;
  document.body.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0, 0, 0);
  const camera = new THREE.PerspectiveCamera(30, 1, 0.1, 100);
  camera.position.set(0, 0, 4);
  camera.lookAt(0, 0, 0);
  const light = new THREE.DirectionalLight(0xffffff, ${Number(intensity)});
  light.position.set(${dir.split(',').map(Number).join(',')});
  scene.add(light);
  const done = () => {
    renderer.render(scene, camera);
    const gl = renderer.getContext();
    const err = gl.getError();
    out.textContent = err ? 'ERROR WebGL error ' + err :
        'PNG ' + renderer.domElement.toDataURL('image/png') + ' ' + THREE.REVISION;
  };
  renderer.debug.onShaderError = (gl, program, vs, fs) => {
    out.textContent = 'ERROR shader: ' + gl.getProgramInfoLog(program) + ' ' +
                      gl.getShaderInfoLog(vs) + ' ' + gl.getShaderInfoLog(fs);
    throw new Error('shader');
  };
  if (${JSON.stringify(isModule)}) {
    import('/model.mjs').then((m) => {
      scene.add(new THREE.Mesh(new THREE.SphereGeometry(1, 128, 64), m.default()));
      try { done(); } catch (e) { if (!out.textContent.startsWith('ERROR')) out.textContent = 'ERROR ' + e; }
    }, (e) => { out.textContent = 'ERROR ' + e; });
  } else {
    new GLTFLoader().load('/model.glb', (gltf) => {
      scene.add(gltf.scene);
      done();
    }, undefined, (e) => { out.textContent = 'ERROR ' + e; });
  }
} catch (e) {
  out.textContent = 'ERROR ' + e;
}
</script></body></html>`;

const server = http.createServer((req, res) => {
  const url = decodeURIComponent(req.url.split('?')[0]);
  let file = null;
  if (url === '/') {
    res.writeHead(200, { 'Content-Type': 'text/html' });
    return res.end(page);
  }
  if (url === '/model.glb' || url === '/model.mjs') file = glb;
  if (url.startsWith('/three/') && !url.includes('..')) file = path.join(three, url.slice(7));
  if (!file || !fs.existsSync(file)) {
    res.writeHead(404);
    return res.end();
  }
  const type = /\.m?js$/.test(file) ? 'text/javascript' : 'application/octet-stream';
  res.writeHead(200, { 'Content-Type': type });
  fs.createReadStream(file).pipe(res);
});

server.listen(0, '127.0.0.1', () => {
  const url = `http://127.0.0.1:${server.address().port}/`;
  const chromium = process.env.CHROMIUM || 'chromium';
  execFile(chromium, ['--headless=new', '--no-sandbox', '--use-angle=swiftshader',
                      '--enable-unsafe-swiftshader', '--disable-gpu-sandbox',
                      '--virtual-time-budget=30000', '--dump-dom', url],
           { maxBuffer: 64 << 20, timeout: 120000 }, (err, stdout, stderr) => {
    server.close();
    const m = /PNG data:image\/png;base64,([A-Za-z0-9+/=]+) (\d+)/.exec(stdout);
    if (!m) {
      const e = /ERROR[^<]*/.exec(stdout);
      console.error(`render_three: no image (${e ? e[0] : err || 'no output'})`);
      process.exit(1);
    }
    fs.writeFileSync(out, Buffer.from(m[1], 'base64'));
    console.log(`render_three: three.js r${m[2]} -> ${out}`);
  });
});
