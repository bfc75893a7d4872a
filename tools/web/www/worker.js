// The render worker: one Player (the kernel compiled to WebAssembly) drawing frame
// after frame off the page's main thread. The page terminates it to cancel a frame
// (a new scene text while one is drawn) and starts another with the compiled module.
//
// Messages in:  {module}                      once, first: the compiled .wasm
//               {id, text?, view, frame}      load `text` if given, apply `view`, draw
//                                             (the view's pairs: tools/web/src/view.rs)
// Messages out: {id, error}                   the text was refused (line, field, reason)
//               {id, failed}                  the view or the frame was refused
//               {id, info?, report, ms, differing, rgba, marks}

import init, { Player } from './pkg/embedded_raytracer_web.js';

let player;
let ready;

self.onmessage = async (event) => {
  const m = event.data;
  if (m.module) {
    ready = init({ module_or_path: m.module }).then(() => { player = new Player(); });
    return;
  }
  await ready;
  self.postMessage(...handle(m));
};

/// A wasm-bindgen object as a plain object the page can receive, freed.
function plain(object, keys) {
  const out = {};
  for (const k of keys) out[k] = object[k];
  object.free();
  return out;
}

function handle({ id, text, view, frame }) {
  let info;
  if (text !== undefined) {
    try {
      info = plain(player.load(text), ['width', 'height', 'frames', 'fps', 'moves', 'features']);
      info.elevation = Array.from(player.elevationRange());
    } catch (e) {
      // A LoadError, or a trap of the module (then the page starts another worker).
      if (e instanceof WebAssembly.RuntimeError) return [{ id, failed: String(e) }];
      return [{ id, error: plain(e, ['line', 'field', 'reason', 'message']) }];
    }
  }
  let report;
  let ms;
  try {
    player.setView(view);
    // The browser's clock (std::time::Instant panics on wasm32): the frame alone.
    const start = performance.now();
    report = player.draw(frame);
    ms = performance.now() - start;
  } catch (e) {
    return [{ id, info, failed: String(e) }];
  }
  report = plain(report, ['frame', 'full', 'traced', 'sent', 'windows', 'arithmetic', 'refused', 'width', 'height']);
  const differing = player.compare();
  const rgba = player.rgba();
  const marks = player.marks();
  return [{ id, info, report, ms, differing, rgba, marks }, [rgba.buffer, marks.buffer]];
}
