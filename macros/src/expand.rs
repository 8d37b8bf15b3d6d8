//! Expansion: validate the description, generate the module, and make the build depend on
//! the description file.

use crate::parse::{Body, RobotInput};
use dhgen_description::{RobotModel, validate};
use quote::{ToTokens, quote};
use std::path::PathBuf;

pub fn expand(input: RobotInput) -> syn::Result<proc_macro2::TokenStream> {
    let RobotInput {
        vis,
        name,
        body,
        options,
        urdf,
    } = input;
    let (at, source) = match &body {
        Body::File(lit) => (lit.span(), format!("{}: ", lit.value())),
        Body::Inline(_) => (name.span(), String::new()),
    };
    let (model, tracking) = match body {
        Body::File(lit) => {
            let dir = std::env::var("CARGO_MANIFEST_DIR").unwrap_or_else(|_| ".".into());
            let path = PathBuf::from(dir).join(lit.value());
            let shown = lit.value();
            // The message names the path as written, not as resolved: the absolute path
            // would differ between machines, and the rule it follows is stated instead.
            let text = std::fs::read_to_string(&path).map_err(|e| {
                syn::Error::new(
                    lit.span(),
                    format!(
                        "{shown}: cannot read file: {e}; the path is relative to the directory \
                         of the invoking crate's Cargo.toml"
                    ),
                )
            })?;
            // `file:line:column: link N, field F: ...`, at the path literal.
            let model = if dhgen_description::urdf::is_urdf_path(&path) {
                dhgen_description::urdf::read(&text, &shown, &urdf.0)
                    .map_err(|e| syn::Error::new(lit.span(), e))?
                    .model
            } else {
                if let Some(at) = urdf.1 {
                    return Err(syn::Error::new(
                        at,
                        "`tip`, `base` and `snap` choose how a URDF file is read; this \
                         description is TOML (a `.urdf` file name selects URDF)",
                    ));
                }
                RobotModel::from_toml_named(&text, &shown)
                    .map_err(|e| syn::Error::new(lit.span(), e))?
            };
            let abs = path.to_string_lossy().into_owned();
            // Editing the file must rebuild the crate.
            (
                model,
                quote!(
                    const _: &[u8] = include_bytes!(#abs);
                ),
            )
        }
        Body::Inline(table) => {
            if let Some(at) = urdf.1 {
                return Err(syn::Error::new(
                    at,
                    "`tip`, `base` and `snap` choose how a URDF file is read; an inline \
                     description has no file to read",
                ));
            }
            let model =
                validate::validate(&table, Some(&name.to_string())).map_err(|e| e.loc.error(&e))?;
            (model, quote!())
        }
    };
    // The generator's own limits (size, finite constants) are reported at the description.
    let generated = dhgen_codegen::generate_with(&model, vis.to_token_stream(), &name, options)
        .map_err(|e| syn::Error::new(at, format!("{source}{e}")))?;
    let tokens = generated.tokens;
    Ok(quote! {
        #tokens
        #tracking
    })
}
