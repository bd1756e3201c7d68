// The 3D view: renderer, camera with orbit controls, lights, the robot from the MJCF geoms, the measured
// contact-force arrows and the ghost of the plan. Renders on demand (when the time, the camera or the size
// changes), so a paused page costs nothing.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { RobotScene } from './robot.js';
import { Ghost } from './ghost.js';
import { Arrow } from './arrow.js';

export class View3D {
  constructor(canvas, sceneData) {
    this.canvas = canvas;
    this.renderer = new THREE.WebGLRenderer({ canvas, antialias: false, powerPreference: 'high-performance' });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0xeef1f5);
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.05, 200);
    this.camera.up.set(0, 0, 1);
    this.camera.position.set(0.9, -2.7, 1.25);
    this.controls = new OrbitControls(this.camera, canvas);
    this.controls.target.set(0, 0, 0.55);
    this.controls.update();
    this.controls.addEventListener('change', () => { this.dirty = true; });
    this.addLights();
    this.world = new RobotScene(sceneData);
    this.scene.add(this.world.root);
    this.ghost = new Ghost();
    this.scene.add(this.ghost.object);
    this.forceArrows = [];
    this.followTarget = new THREE.Vector3();
    this.lastFollow = null;
    this.dirty = true;
    this.frames = 0;
    this.scale = 1;  // resolution scale of the adaptive replay (1 = full)
  }

  /** Render at `scale` x the device resolution (the canvas keeps its size on the page). */
  setScale(scale) {
    if (scale === this.scale) return;
    this.scale = scale;
    this.renderer.setPixelRatio(scale * Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setSize(this.canvas.clientWidth, this.canvas.clientHeight, false);
    this.dirty = true;
  }

  addLights() {
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8d8a84, 1.8));
    const sun = new THREE.DirectionalLight(0xffffff, 2.0);
    sun.position.set(1.5, -2.0, 5.0);
    this.scene.add(sun);
  }

  /**
   * Blob shadows on the ground under the given body slots (the pelvis and the wheels): darker and smaller the
   * closer the body is to the ground, so the flight phase reads at a glance. Cheap where shadow maps are not
   * (software WebGL).
   */
  setShadowBodies(slots, radii) {
    for (const s of this.blobs || []) this.scene.remove(s.mesh);
    this.blobs = slots.map((slot, i) => {
      const mesh = new THREE.Mesh(new THREE.CircleGeometry(1, 32), new THREE.MeshBasicMaterial({
        color: 0x20242c, transparent: true, opacity: 0.3, depthWrite: false,
      }));
      mesh.renderOrder = 1;
      this.scene.add(mesh);
      return { slot, radius: radii[i], mesh };
    });
  }

  updateShadows() {
    for (const b of this.blobs || []) {
      const body = this.world.bodies[b.slot];
      const h = Math.max(0, body.position.z);
      b.mesh.visible = this.world.robot.visible;
      b.mesh.position.set(body.position.x, body.position.y, 0.002);
      b.mesh.scale.set(b.radius[0] * (1 + 0.3 * h), b.radius[1] * (1 + 0.3 * h), 1);
      b.mesh.material.opacity = 0.35 * Math.max(0.15, 1 - 0.8 * h);
    }
  }

  /** One measured-force arrow per contact body. */
  setContactCount(n) {
    while (this.forceArrows.length < n) {
      const a = new Arrow(0xd0342c, 0.9);
      this.forceArrows.push(a);
      this.scene.add(a.object);
    }
    this.forceArrows.forEach((a, i) => { a.object.visible = a.object.visible && i < n; });
  }

  resize() {
    const w = this.canvas.clientWidth, h = this.canvas.clientHeight;
    if (w === 0 || h === 0) return;
    const size = this.renderer.getSize(new THREE.Vector2());
    if (size.x === w && size.y === h) return;
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  /** Keep the camera's offset to `p` (the pelvis) while following; the first call only records it. */
  follow(p, enabled) {
    if (!enabled) {
      this.lastFollow = null;
      return;
    }
    if (this.lastFollow) {
      const dx = p.x - this.lastFollow.x, dy = p.y - this.lastFollow.y;
      this.camera.position.x += dx;
      this.camera.position.y += dy;
      this.controls.target.x += dx;
      this.controls.target.y += dy;
      this.controls.update();
    }
    this.lastFollow = p.clone();
  }

  render() {
    this.resize();
    this.updateShadows();
    this.renderer.render(this.scene, this.camera);
    this.dirty = false;
    this.frames++;
  }
}
