// The page's style sheet, injected by the bundle (the page is one file).

export const kColors = {
  fixed: '#8a8f98',
  judged: '#d9b26f',
  gripped: '#3aa655',
  carried: '#3bb0b8',
  tool: '#8e5bd6',
  failed: '#e0312b',
  fixel: '#d6338a',
  held: '#4b6ea8',
  free: '#17a589',
  normal: '#1f5fd1',
  friction: '#f08a00',
  pairLight: '#8fbcf2',
  pairDark: '#0b2566',
  pivot: '#111111',
};

export const kCss = `
:root { --bg:#f6f5f2; --panel:#ffffff; --ink:#1d1f23; --muted:#6a6f78; --line:#dedbd4; }
* { box-sizing: border-box; }
html, body { margin:0; height:100%; background:var(--bg); color:var(--ink);
  font: 13px/1.4 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", sans-serif; }
#cairn-app { display:grid; height:100vh; grid-template-columns: 1fr 320px;
  grid-template-rows: auto 1fr auto; grid-template-areas: "head head" "view side" "foot side"; }
header { grid-area:head; display:flex; align-items:center; gap:12px; padding:8px 14px;
  border-bottom:1px solid var(--line); background:var(--panel); }
header h1 { font-size:15px; margin:0; font-weight:600; }
header .kind { color:var(--muted); }
.badge { padding:2px 10px; border-radius:10px; color:#fff; font-weight:600; letter-spacing:.02em; }
.badge.good { background:#2f8f46; } .badge.bad { background:#c62d26; } .badge.warn { background:#c27c0e; }
#view { grid-area:view; position:relative; min-height:200px; overflow:hidden; }
#view canvas { display:block; width:100%; height:100%; }
#tip { position:absolute; pointer-events:none; background:rgba(20,22,26,.88); color:#fff; padding:6px 8px;
  border-radius:4px; font-size:12px; white-space:pre; display:none; z-index:3; }
#overlay { position:absolute; left:10px; top:8px; font-size:12px; color:var(--muted); z-index:2;
  background:rgba(246,245,242,.8); padding:4px 6px; border-radius:4px; }
aside { grid-area:side; border-left:1px solid var(--line); background:var(--panel); overflow:auto; padding:10px 12px; }
aside h2 { font-size:12px; text-transform:uppercase; letter-spacing:.06em; color:var(--muted); margin:14px 0 6px; }
aside h2:first-child { margin-top:0; }
.legend div { display:flex; align-items:center; gap:6px; margin:2px 0; }
.sw { width:12px; flex:none; height:12px; border-radius:2px; display:inline-block; border:1px solid rgba(0,0,0,.2); }
#info { white-space:pre-wrap; font-family: ui-monospace, "DejaVu Sans Mono", monospace; font-size:12px;
  background:#f3f2ef; padding:6px; border-radius:4px; min-height:3em; }
#story { margin:0; padding-left:16px; } #story li { margin:3px 0; }
#solver-notes { margin-top:6px; color:var(--muted); font-size:12px; }
#solver-notes ul { margin:4px 0; padding-left:16px; } #solver-notes li { margin:2px 0; }
footer { grid-area:foot; border-top:1px solid var(--line); background:var(--panel); padding:6px 12px; }
footer .row { display:flex; align-items:center; gap:10px; }
footer button { font:inherit; padding:3px 12px; border:1px solid var(--line); border-radius:4px; background:#fff; cursor:pointer; }
footer button:hover { background:#f0efec; }
#scrub-wrap { position:relative; flex:1; }
#scrub { width:100%; }
.mark { position:absolute; top:-2px; width:3px; height:8px; background:#c62d26; border-radius:1px; pointer-events:none; }
#time { min-width:15em; font-family: ui-monospace, "DejaVu Sans Mono", monospace; font-size:12px; }
#chart { width:100%; height:150px; display:block; margin-top:2px; }
footer select { font:inherit; max-width:60%; }
#seqs { list-style:none; margin:0; padding:0; }
#seqs li { padding:4px 6px; border-radius:4px; cursor:pointer; margin:1px 0; }
#seqs li.on { background:#e9eefb; }
#seqs li .warn { color:#c27c0e; font-weight:600; }
.steps { margin:4px 0 0 0; padding-left:18px; } .steps li.now { font-weight:600; }
.note { color:var(--muted); font-size:12px; }
.labels { position:absolute; inset:0; pointer-events:none; z-index:2; overflow:hidden; }
.label { position:absolute; left:0; top:0; display:none; white-space:nowrap; font-size:12px; font-weight:600;
  padding:1px 6px; border-radius:9px; background:rgba(255,255,255,.92); border:2px solid #8a8f98; color:var(--ink); }
.label.failed { border-color:#e0312b; } .label.gripped { border-color:#3aa655; } .label.held { border-color:#4b6ea8; }
.label.fixel { border-color:#d6338a; } .label.carried { border-color:#3bb0b8; }
.label.free { border-color:#17a589; }
.label.joint { border-color:#0b2566; font-weight:500; }
label.ctl { display:flex; align-items:center; gap:6px; margin:3px 0; }
`;
