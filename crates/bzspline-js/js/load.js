// Instantiates one of the package's WebAssembly modules next to this file:
// read from disk where the package is a file (Node, Deno, Bun), fetched
// where it is served (a browser, with or without a bundler).
export async function load(init, initSync, url) {
  if (url.protocol === "file:") {
    const { readFile } = await import("node:fs/promises");
    initSync({ module: await readFile(url) });
  } else {
    await init({ module_or_path: url });
  }
}
